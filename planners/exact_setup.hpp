#pragma once
// The exact planning setup of one scenario, wired once for every user (svmp-plan's runs,
// bench/experiments/experiment.cpp; our planners in OMPL, planners/ompl/scenario_setup.hpp): the
// configuration space, the FCL checker, the thesis' sampled validator at the scenario's resolution,
// the certified validator (cspace/certified_motion_validator.hpp) and the path repairer
// (planners/verify_repair.hpp). `exact` plans on FCL with the certifier; `planning` adds the repairer,
// so a non-roadmap planner's segment that clips a corner between sampled checks is replanned.
// Lifetime: holds references to its own members (neither copyable nor movable). Thread safety: const
// members, concurrent as each of them is.
#include "cspace/certified_motion_validator.hpp"
#include "cspace/collision_checker.hpp"
#include "cspace/scenario/scenario.hpp"
#include "planners/planner.hpp"
#include "planners/verify_repair.hpp"

namespace svmp::planners {

struct ExactSetup {
  ExactSetup(const cspace::Scenario& scenario, int threads);
  ExactSetup(const ExactSetup&) = delete;
  ExactSetup& operator=(const ExactSetup&) = delete;

  const cspace::ConfigurationSpace space;
  const cspace::CollisionChecker checker;
  const cspace::DiscreteMotionValidator validator;
  const cspace::CertifiedMotionValidator certifier;
  const PlanningContext exact;           // checker, sampled validator, certifier
  const PlanningContext repair_context;  // repairs accept only segments the certifier proves
  const PathRepairer repairer;
  const PlanningContext planning;        // exact + repairer
};

}  // namespace svmp::planners
