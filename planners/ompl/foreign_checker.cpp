#include "planners/ompl/foreign_checker.hpp"

#include "planners/ompl/state_bridge.hpp"

#include <ompl/base/spaces/RealVectorStateSpace.h>

#include <stdexcept>

namespace svmp::ompl_planners {
namespace {

// An OMPL state holding q * scale, freed when it leaves scope.
class StateOf {
 public:
  StateOf(const ob::SpaceInformation& si, const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::VectorXd& scale)
      : si_(si), state_(si.allocState()) {
    toState(q, scale, state_);
  }
  ~StateOf() { si_.freeState(state_); }
  StateOf(const StateOf&) = delete;
  StateOf& operator=(const StateOf&) = delete;
  ob::State* get() const { return state_; }

 private:
  const ob::SpaceInformation& si_;
  ob::State* state_;
};

cspace::Environment singleClass() {
  cspace::Obstacle invalid;
  invalid.name = "invalid under the SpaceInformation's StateValidityChecker";
  invalid.shape = robots::Shape::sphere(1.0);  // never used for geometry: no robot to place
  return cspace::Environment({invalid});
}

}  // namespace

cspace::ConfigurationSpace configurationSpaceOf(const ob::SpaceInformation& si) {
  const auto* space = dynamic_cast<const ob::RealVectorStateSpace*>(si.getStateSpace().get());
  if (!space) throw std::invalid_argument("the state space '" + si.getStateSpace()->getName() +
                                          "' is not an ompl::base::RealVectorStateSpace");
  const auto& bounds = space->getBounds();
  const int dim = static_cast<int>(space->getDimension());
  Eigen::VectorXd lower(dim), upper(dim);
  for (int i = 0; i < dim; ++i) lower[i] = bounds.low[i], upper[i] = bounds.high[i];
  return cspace::ConfigurationSpace(lower, upper, Eigen::VectorXd::Ones(dim));
}

ForeignValidityChecker::ForeignValidityChecker(ob::SpaceInformationPtr si)
    : si_(std::move(si)), environment_(singleClass()), scale_(Eigen::VectorXd::Ones(si_->getStateDimension())) {}

const robots::Robot& ForeignValidityChecker::robot() const {
  throw std::logic_error("the SpaceInformation's StateValidityChecker is not svmp's: it has no robot model");
}

int ForeignValidityChecker::check(const Eigen::Ref<const Eigen::VectorXd>& q) const {
  checks_.fetch_add(1, std::memory_order_relaxed);
  const StateOf state(*si_, q, scale_);
  return si_->isValid(state.get()) ? cspace::kFree : 1;
}

bool ForeignValidityChecker::hits(const Eigen::Ref<const Eigen::VectorXd>& q, int id) const {
  return id == 1 && check(q) == 1;
}

double ForeignValidityChecker::clearance(const Eigen::Ref<const Eigen::VectorXd>& q) const {
  const StateOf state(*si_, q, scale_);
  return si_->getStateValidityChecker()->clearance(state.get());
}

ForeignMotionValidator::ForeignMotionValidator(ob::SpaceInformationPtr si, const cspace::ValidityChecker& checker,
                                               const cspace::ConfigurationSpace& space)
    : si_(std::move(si)), checker_(checker), space_(space) {}

bool ForeignMotionValidator::isValid(const Eigen::Ref<const Eigen::VectorXd>& a,
                                     const Eigen::Ref<const Eigen::VectorXd>& b) const {
  countCall();
  const StateOf sa(*si_, a, space_.metricScale()), sb(*si_, b, space_.metricScale());
  return si_->checkMotion(sa.get(), sb.get());
}

bool ForeignMotionValidator::checkMotion(const Eigen::Ref<const Eigen::VectorXd>& a,
                                         const Eigen::Ref<const Eigen::VectorXd>& b, double& last_valid) const {
  countCall();
  const StateOf sa(*si_, a, space_.metricScale()), sb(*si_, b, space_.metricScale());
  std::pair<ob::State*, double> last{nullptr, 0.0};
  const bool ok = si_->getMotionValidator()->checkMotion(sa.get(), sb.get(), last);
  last_valid = ok ? 1.0 : last.second;
  return ok;
}

double ForeignMotionValidator::resolution() const {
  return si_->getStateValidityCheckingResolution() * si_->getMaximumExtent();
}

}  // namespace svmp::ompl_planners
