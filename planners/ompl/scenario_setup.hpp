#pragma once
// A scenario ready for OMPL (OMPL 1.5 API: ompl::base::SpaceInformation, ompl::geometric::SimpleSetup):
// the configuration space, the FCL checker, the sampled validator at the scenario's resolution, the
// certified validator and the path repairer, wired as svmp-plan wires them
// (bench/experiments/experiment.cpp, World), behind our checker as OMPL's (planners/ompl/state_bridge.hpp).
// Any OMPL planner plans on it; ours (planners/ompl/svm_planners.hpp) recover the whole context from
// it and certify their paths.
//
// Lifetime: every SpaceInformation made here keeps the world alive. Thread safety: const methods are
// concurrent; a SimpleSetup is one caller's.
#include <ompl/geometric/SimpleSetup.h>

#include <memory>

#include "cspace/certified_motion_validator.hpp"
#include "cspace/collision_checker.hpp"
#include "cspace/scenario/scenario.hpp"
#include "planners/ompl/state_bridge.hpp"
#include "planners/verify_repair.hpp"

namespace svmp::ompl_planners {

namespace og = ::ompl::geometric;

class ScenarioWorld : public std::enable_shared_from_this<ScenarioWorld> {
 public:
  // `threads`: PlanningContext::threads of our planners (OpenMP inside a call).
  static std::shared_ptr<const ScenarioWorld> make(cspace::Scenario scenario, int threads = 1);

  // A new SpaceInformation with our checker and validator, set up.
  ob::SpaceInformationPtr spaceInformation() const;
  // A SimpleSetup on a new SpaceInformation with the query's start and goal (default: the first).
  std::shared_ptr<og::SimpleSetup> simpleSetup(int query = 0) const;

  const cspace::Scenario& scenario() const { return scenario_; }
  const planners::PlanningContext& context() const { return context_; }
  const cspace::CollisionChecker& checker() const { return checker_; }

 private:
  ScenarioWorld(cspace::Scenario scenario, int threads);

  const cspace::Scenario scenario_;
  const cspace::ConfigurationSpace space_;
  const cspace::CollisionChecker checker_;
  const cspace::DiscreteMotionValidator validator_;
  const cspace::CertifiedMotionValidator certifier_;
  const planners::PlanningContext repair_context_;  // repairs accept only segments the certifier proves
  const planners::PathRepairer repairer_;
  const planners::PlanningContext context_;
};

}  // namespace svmp::ompl_planners
