#include "planners/exact_setup.hpp"

namespace svmp::planners {

ExactSetup::ExactSetup(const cspace::Scenario& scenario, int threads)
    : space(scenario.makeSpace()),
      checker(scenario.robot, scenario.environment, scenario.self_collision),
      validator(checker, space, scenario.resolution),
      certifier(checker, space, scenario.resolution),
      exact{space, checker, validator, threads, &certifier},
      repair_context{space, checker, certifier, threads, &certifier},
      repairer(repair_context),
      planning{space, checker, validator, threads, &certifier, &repairer} {}

}  // namespace svmp::planners
