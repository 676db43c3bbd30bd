#pragma once
// Scenario files (YAML, bench/scenarios/): robot, obstacles, queries, checking resolution, metric
// weights and per-planner parameters. The schema is documented in docs/scenarios.md. Every error
// throws ScenarioError whose message names the file, the field and the offending value.
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "cspace/configuration_space.hpp"
#include "cspace/environment.hpp"
#include "cspace/scenario/parameters.hpp"
#include "robots/robot.hpp"

namespace svmp::cspace {

struct Query {
  Eigen::VectorXd start, goal;
  // Optional waypoints (start and goal excluded) of a known collision-free path: the scenario file's
  // proof by construction that the query has a solution. Empty when the file gives none.
  std::vector<Eigen::VectorXd> witness;
};

struct Scenario {
  std::string path;
  std::string name;
  std::string description;
  std::shared_ptr<const robots::Robot> robot;
  std::shared_ptr<const Environment> environment;
  std::vector<Query> queries;
  double resolution = 0.01;  // checking resolution in the weighted metric
  Eigen::VectorXd metric_weights;
  bool self_collision = true;
  std::map<std::string, ParameterSet> planner_params;  // by planner name; absent planners get defaults

  ConfigurationSpace makeSpace() const;
  // The parameters of one planner (empty set with the right error prefix when the file has none).
  ParameterSet paramsFor(const std::string& planner) const;
};

Scenario loadScenario(const std::string& path);
// Same, from YAML text; `source` names it in errors.
Scenario parseScenario(const std::string& yaml_text, const std::string& source);

}  // namespace svmp::cspace
