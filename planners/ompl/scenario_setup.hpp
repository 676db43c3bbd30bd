#pragma once
// A scenario ready for OMPL (OMPL 1.5 API: ompl::base::SpaceInformation, ompl::geometric::SimpleSetup):
// the configuration space, the FCL checker, the sampled validator at the scenario's resolution, the
// certified validator and the path repairer, wired as svmp-plan wires them (planners/exact_setup.hpp),
// behind our checker as OMPL's (planners/ompl/state_bridge.hpp).
// Any OMPL planner plans on it; ours (planners/ompl/svm_planners.hpp) recover the whole context from
// it and certify their paths.
//
// Lifetime: every SpaceInformation made here keeps the world alive. Thread safety: const methods are
// concurrent; a SimpleSetup is one caller's.
#include <ompl/geometric/SimpleSetup.h>

#include <memory>

#include "cspace/scenario/scenario.hpp"
#include "planners/exact_setup.hpp"
#include "planners/ompl/state_bridge.hpp"

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
  const planners::PlanningContext& context() const { return setup_.planning; }
  const cspace::CollisionChecker& checker() const { return setup_.checker; }

 private:
  ScenarioWorld(cspace::Scenario scenario, int threads);

  const cspace::Scenario scenario_;
  const planners::ExactSetup setup_;
};

}  // namespace svmp::ompl_planners
