// Trust: on every scenario file in bench/scenarios, every planner run through the driver reports solved
// only for a certified path, and every certified path also passes a dense independent re-check (FCL at
// 1/16 of the resolution, end points included).
#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>

#include "bench/experiments/experiment.hpp"
#include "cspace/collision_checker.hpp"
#include "planners/planner_registry.hpp"
#include "robots/point_robot.hpp"

namespace svmp::planners {
namespace {

bool denselyFree(const cspace::Scenario& scenario, const std::vector<Eigen::VectorXd>& path) {
  const cspace::ConfigurationSpace space = scenario.makeSpace();
  const cspace::CollisionChecker checker(scenario.robot, scenario.environment, scenario.self_collision);
  const double step = scenario.resolution / 16;
  for (size_t i = 0; i + 1 < path.size(); ++i) {
    const int n = std::max(1, static_cast<int>(std::ceil(space.distance(path[i], path[i + 1]) / step)));
    for (int k = 0; k <= n; ++k)
      if (!checker.isValid(path[i] + (static_cast<double>(k) / n) * (path[i + 1] - path[i]))) return false;
  }
  return true;
}

TEST(CertifiedPaths, EveryPlannerOnEveryScenarioReturnsOnlyCertifiedPaths) {
  const std::filesystem::path dir = std::filesystem::path(SVMP_SOURCE_DIR) / "bench/scenarios";
  int solved = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() != ".yaml") continue;
    const cspace::Scenario scenario = cspace::loadScenario(entry.path().string());
    experiments::DriverOptions options;
    options.scenario = entry.path().string();
    options.planners = {"svmp", "prm"};
    if (scenario.name.rfind("thesis_fig2", 0) == 0) options.planners.push_back("local");
    if (dynamic_cast<const robots::PointRobot*>(scenario.robot.get())) options.planners.push_back("svpp");
    const auto names = plannerNames();
    if (std::find(names.begin(), names.end(), "ompl-rrtconnect") != names.end())
      options.planners.push_back("ompl-rrtconnect");
    options.runs = 1;
    options.time_limit = 20;
    std::ostringstream log;
    for (const auto& runs : experiments::runExperiment(scenario, options, log))
      for (const auto& r : runs.runs) {
        SCOPED_TRACE(scenario.name + " " + runs.planner);
        if (!r.result.solved()) continue;
        ++solved;
        EXPECT_TRUE(r.result.certified);
        EXPECT_TRUE(denselyFree(scenario, r.result.path));
        EXPECT_GT(r.result.distance_queries, 0u);
      }
  }
  EXPECT_GT(solved, 20);
}

}  // namespace
}  // namespace svmp::planners
