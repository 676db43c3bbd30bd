#include "planners/ompl/state_bridge.hpp"

#include <algorithm>
#include <utility>
#include <vector>

#include <ompl/base/spaces/RealVectorStateProjections.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>

namespace svmp::ompl_planners {

ob::PlannerStatus omplStatus(planners::PlanStatus status) {
  using planners::PlanStatus;
  switch (status) {
    case PlanStatus::kSolved: return ob::PlannerStatus::EXACT_SOLUTION;
    case PlanStatus::kLocalMinimum: return ob::PlannerStatus::APPROXIMATE_SOLUTION;
    case PlanStatus::kTimeout: return ob::PlannerStatus::TIMEOUT;
    case PlanStatus::kInvalidStart: return ob::PlannerStatus::INVALID_START;
    case PlanStatus::kInvalidGoal: return ob::PlannerStatus::INVALID_GOAL;
    case PlanStatus::kFailed:
    case PlanStatus::kInvalidInput: break;
  }
  return ob::PlannerStatus::ABORT;
}

Eigen::VectorXd toConfiguration(const ob::State* state, const cspace::ConfigurationSpace& space) {
  const auto* v = state->as<ob::RealVectorStateSpace::StateType>();
  const Eigen::VectorXd& scale = space.metricScale();
  Eigen::VectorXd q(scale.size());
  for (int i = 0; i < q.size(); ++i) q[i] = std::clamp(v->values[i] / scale[i], space.lower()[i], space.upper()[i]);
  return q;
}

void toState(const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::VectorXd& scale, ob::State* state) {
  auto* v = state->as<ob::RealVectorStateSpace::StateType>();
  for (int i = 0; i < q.size(); ++i) v->values[i] = q[i] * scale[i];
}

ContextValidityChecker::ContextValidityChecker(const ob::SpaceInformationPtr& si,
                                               const planners::PlanningContext& context,
                                               std::shared_ptr<const void> owner)
    : ob::StateValidityChecker(si), context_(context), owner_(std::move(owner)) {
  // FCL's distance, which may overestimate by millimetres (docs/architecture.md, "Seams").
  specs_.clearanceComputationType = ob::StateValidityCheckerSpecs::APPROXIMATE;
}

bool ContextValidityChecker::isValid(const ob::State* state) const {
  return context_.checker.isValid(toConfiguration(state, context_.space));
}

double ContextValidityChecker::clearance(const ob::State* state) const {
  return context_.checker.clearance(toConfiguration(state, context_.space));
}

ContextMotionValidator::ContextMotionValidator(const ob::SpaceInformationPtr& si,
                                               const planners::PlanningContext& context,
                                               std::shared_ptr<const void> owner)
    : ob::MotionValidator(si), context_(context), owner_(std::move(owner)) {}

bool ContextMotionValidator::checkMotion(const ob::State* s1, const ob::State* s2) const {
  const bool ok = context_.validator.isValidIncludingEnd(toConfiguration(s1, context_.space), toConfiguration(s2, context_.space));
  ok ? ++valid_ : ++invalid_;
  return ok;
}

bool ContextMotionValidator::checkMotion(const ob::State* s1, const ob::State* s2,
                                         std::pair<ob::State*, double>& last_valid) const {
  double t = 0;
  if (context_.validator.checkMotion(toConfiguration(s1, context_.space), toConfiguration(s2, context_.space), t)) {
    ++valid_;
    return true;
  }
  last_valid.second = t;
  if (last_valid.first) si_->getStateSpace()->interpolate(s1, s2, t, last_valid.first);
  ++invalid_;
  return false;
}

namespace {

// OMPL's informed samplers (Informed RRT*'s PathLengthDirectInfSampler) draw through the space's
// *default* sampler, which RealVectorStateSpace seeds from OMPL's process-wide generator, so
// ompl-informedrrtstar's runs differed for a seed. Here the default is the bridge's seeded sampler
// too (kept apart from the allocator a user may set later); no other planner the bridge builds asks
// for the default one.
class SeededDefaultSpace final : public ob::RealVectorStateSpace {
 public:
  SeededDefaultSpace(unsigned int dim, ob::StateSamplerAllocator sampler)
      : ob::RealVectorStateSpace(dim), sampler_(std::move(sampler)) {}
  ob::StateSamplerPtr allocDefaultStateSampler() const override { return sampler_(this); }

 private:
  ob::StateSamplerAllocator sampler_;
};

}  // namespace

ob::SpaceInformationPtr makeSpaceInformation(const planners::PlanningContext& context,
                                             std::shared_ptr<const void> owner,
                                             const ob::StateSamplerAllocator& sampler) {
  const Eigen::VectorXd& scale = context.space.metricScale();
  const int dim = context.space.dim();
  const auto space = sampler ? std::make_shared<SeededDefaultSpace>(dim, sampler)
                             : std::make_shared<ob::RealVectorStateSpace>(dim);
  ob::RealVectorBounds bounds(dim);
  for (int i = 0; i < dim; ++i) {
    bounds.setLow(i, context.space.lower()[i] * scale[i]);
    bounds.setHigh(i, context.space.upper()[i] * scale[i]);
  }
  space->setBounds(bounds);
  if (sampler) space->setStateSamplerAllocator(sampler);
  // The default projection (SBL's grid) is on the first two coordinates, an arm's base joints: OMPL's
  // own beyond 2-D is a random linear projection drawn from its process-wide generator, so SBL's runs
  // did not repeat for a seed (Fig 4.6, the Panda: every run differed). With its cell sizes set
  // (OMPL's default: the bounds in 20 cells) the projection counts as the user's, so the space's
  // setup keeps it, sets it up and lists its parameters; one registered after setup would leave the
  // space's ParamSet bound to the projection it replaced (freed). Orthogonal, not linear: a linear
  // projection's Eigen matrix would be freed inside libompl, whose Eigen may align differently from
  // ours (SVMP_NATIVE).
  const int projected = std::min(dim, 2);
  std::vector<unsigned int> coordinates(projected);
  std::vector<double> cells(projected);
  for (int i = 0; i < projected; ++i) coordinates[i] = i, cells[i] = (bounds.high[i] - bounds.low[i]) / 20.0;
  auto projection = std::make_shared<ob::RealVectorOrthogonalProjectionEvaluator>(space, coordinates);
  projection->setCellSizes(cells);
  space->registerDefaultProjection(projection);
  auto si = std::make_shared<ob::SpaceInformation>(space);
  si->setStateValidityChecker(std::make_shared<ContextValidityChecker>(si, context, owner));
  si->setMotionValidator(std::make_shared<ContextMotionValidator>(si, context, owner));
  si->setup();
  return si;
}

}  // namespace svmp::ompl_planners
