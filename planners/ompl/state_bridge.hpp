#pragma once
// Our seams as OMPL's (Sucan, Moll, Kavraki, "The Open Motion Planning Library", IEEE RAM 2012; OMPL 1.5
// API: ompl::base::StateValidityChecker, MotionValidator, SpaceInformation). OMPL states hold a
// configuration q scaled by sqrt(w) (ConfigurationSpace::metricScale), so OMPL's Euclidean distance on
// them is the weighted metric of thesis eq. 4.3 and OMPL's nearest neighbours, ranges and path lengths
// agree with ours. The OMPL bridge (planners/ompl_bridge.cpp) and our planners as OMPL planners
// (planners/ompl/svm_planners.hpp) both plan through these.
//
// ContextValidityChecker is "our own checker": an OMPL planner that finds it in a SpaceInformation
// recovers the whole PlanningContext (obstacle ids, robot, certifier), not only validity.
//
// Thread safety: both classes are const and forward to the context's checker and validator, whose
// const methods are concurrent (OMPL's PRM checks from a second thread).
#include <ompl/base/MotionValidator.h>
#include <ompl/base/PlannerStatus.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/StateValidityChecker.h>

#include <Eigen/Core>
#include <memory>

#include "planners/planner.hpp"

namespace svmp::ompl_planners {

namespace ob = ::ompl::base;

// Our status as OMPL's: kSolved EXACT_SOLUTION, kLocalMinimum APPROXIMATE_SOLUTION (a partial path),
// kTimeout TIMEOUT, kInvalidStart / kInvalidGoal INVALID_START / INVALID_GOAL, otherwise ABORT.
ob::PlannerStatus omplStatus(planners::PlanStatus status);

// A RealVectorStateSpace state as a configuration of `space`: divided by its metric scale coordinate by
// coordinate, and kept within its joint limits, which the round trip q * s / s can pass by one unit in
// the last place (2.8973 * sqrt(2) / sqrt(2) = 2.8973000000000004, beyond the Panda's limit: a valid
// goal became invalid in OMPL, and FMT* then dereferenced a null goal).
Eigen::VectorXd toConfiguration(const ob::State* state, const cspace::ConfigurationSpace& space);
// Writes q * scale into a RealVectorStateSpace state.
void toState(const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::VectorXd& scale, ob::State* state);

// Our validity checker as OMPL's. `owner` keeps alive what the context refers to (may be null when
// the caller guarantees it outlives every use).
class ContextValidityChecker final : public ob::StateValidityChecker {
 public:
  ContextValidityChecker(const ob::SpaceInformationPtr& si, const planners::PlanningContext& context,
                         std::shared_ptr<const void> owner = {});
  bool isValid(const ob::State* state) const override;
  // The FCL distance to the real obstacles (OMPL's PathGeometric::clearance reports it).
  double clearance(const ob::State* state) const override;
  const planners::PlanningContext& context() const { return context_; }
  const std::shared_ptr<const void>& owner() const { return owner_; }

 private:
  planners::PlanningContext context_;
  std::shared_ptr<const void> owner_;
};

// Our straight-line validator as OMPL's (both checkMotion forms; OMPL's valid/invalid motion counters
// are kept, so Benchmark's "valid segment fraction" is right).
class ContextMotionValidator final : public ob::MotionValidator {
 public:
  ContextMotionValidator(const ob::SpaceInformationPtr& si, const planners::PlanningContext& context,
                         std::shared_ptr<const void> owner = {});
  // OMPL's contract: s1 is valid; s2 and the interior are checked.
  bool checkMotion(const ob::State* s1, const ob::State* s2) const override;
  bool checkMotion(const ob::State* s1, const ob::State* s2,
                   std::pair<ob::State*, double>& last_valid) const override;

 private:
  planners::PlanningContext context_;
  std::shared_ptr<const void> owner_;
};

// A RealVectorStateSpace on scaled coordinates within the space's bounds, with the context's checker
// and validator (and `sampler`, when given, also as the default sampler informed samplers draw
// through) installed, set up. The default projection is on the first two coordinates (all of them
// in 1-D and 2-D): OMPL 1.5's identity projection resizes an Eigen::Ref and aborts in Debian's
// build, and its random projection beyond 2-D does not follow the run's seed (SBL, KPIECE).
ob::SpaceInformationPtr makeSpaceInformation(const planners::PlanningContext& context,
                                             std::shared_ptr<const void> owner = {},
                                             const ob::StateSamplerAllocator& sampler = {});

}  // namespace svmp::ompl_planners
