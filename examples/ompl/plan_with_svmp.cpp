// The README's example of SVMP as an OMPL planner (planners/ompl/svm_planners.hpp): a scenario file in
// OMPL's SimpleSetup with our checker, SVMP with the file's parameters and one set through OMPL's
// ParamSet, the certified path printed one configuration a line. usage: svmp-ompl-example [SCENARIO]
#include <iostream>

#include "cspace/scenario/scenario.hpp"
#include "planners/ompl/scenario_setup.hpp"
#include "planners/ompl/svm_planners.hpp"

int main(int argc, char** argv) try {
  namespace sop = svmp::ompl_planners;
  auto world = sop::ScenarioWorld::make(svmp::cspace::loadScenario(argc > 1 ? argv[1] : "bench/scenarios/thesis_fig3_5.yaml"));
  auto setup = world->simpleSetup();  // SimpleSetup on our FCL checker and validator
  auto svmp = std::make_shared<sop::SvmpOmplPlanner>(setup->getSpaceInformation(), world->scenario().paramsFor("svmp"));
  svmp->params().setParam("repair_rounds", "10");  // any field of SvmpOptions, checked as in a scenario file
  setup->setPlanner(svmp);
  if (setup->solve(5.0) != ompl::base::PlannerStatus::EXACT_SOLUTION) {
    std::cerr << "svmp-ompl-example: no path: " << svmp->lastResult().message << "\n";
    return 1;
  }
  // Every segment certified collision-free. The configurations, one a line: OMPL's own states are
  // q * sqrt(w) where the scenario weighs its joints (metric_weights), so printAsMatrix would show those.
  std::cout.precision(17);
  for (const auto& q : svmp->lastResult().path)
    for (int i = 0; i < q.size(); ++i) std::cout << q[i] << (i + 1 < q.size() ? " " : "\n");
  std::cerr << svmp->lastResult().collision_checks << " collision checks, " << svmp->lastResult().milestones
            << " milestones\n";
} catch (const std::exception& e) {
  std::cerr << "svmp-ompl-example: " << e.what() << "\n";
  return 2;
}
