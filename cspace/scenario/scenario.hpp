#pragma once
// Scenario files (YAML, bench/scenarios/): robot, obstacles, queries, checking resolution, metric
// weights and per-planner parameters. The schema is documented in docs/scenarios.md. Every error
// throws ScenarioError whose message names the file, the field and the offending value: unknown or
// duplicate keys, wrong node kinds, values outside the ranges below, oversized inputs, YAML syntax.
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "cspace/configuration_space.hpp"
#include "cspace/environment.hpp"
#include "cspace/scenario/parameters.hpp"
#include "robots/robot.hpp"

namespace svmp::cspace {

// What the loader accepts (docs/scenarios.md, "Limits"). Lengths in m, angles in rad.
struct ScenarioLimits {
  static constexpr std::uintmax_t kMaxFileBytes = 16u << 20;  // checked before parsing
  static constexpr long kMaxYamlNodes = 1'000'000;          // scalars + lists + mappings (~0.5 GB parsed)
  static constexpr int kMaxJoints = 64;                      // planar links, DH rows
  static constexpr int kMaxToolShapes = 1'000;
  static constexpr int kMaxObstacles = 10'000;
  static constexpr int kMaxQueries = 10'000;
  static constexpr int kMaxWitnessWaypoints = 100'000;       // per query
  static constexpr double kMaxCoordinate = 1e6;              // |bounds|, |joint limits|, |positions|
  static constexpr double kMinLength = 1e-9;                 // link lengths, widths, radii, box sides
  static constexpr double kMaxLength = 1e4;
  static constexpr double kMaxDhLength = 1e4;                // |DH a|, |DH d| (rows and flange)
  static constexpr double kMaxAngle = 1e3;                   // |DH alpha|, |DH offset|, |rpy|
  static constexpr double kMinResolution = 1e-9;
  static constexpr double kMaxResolution = 1e6;
  // Checks along the whole C-space diagonal, sqrt(sum_d w_d (upper_d - lower_d)^2) / resolution.
  static constexpr double kMaxChecksPerDiagonal = 1073741824.0;  // 2^30
  static constexpr double kMaxWeight = 1e6;                  // metric weights, obstacle weights: (0, max]
};

struct Query {
  Eigen::VectorXd start, goal;
  // Optional waypoints (start and goal excluded) of a known collision-free path: the scenario file's
  // proof by construction that the query has a solution. Empty when the file gives none.
  std::vector<Eigen::VectorXd> witness;
  // start, the witness' waypoints, goal: the path the file proves (empty when it gives no witness).
  std::vector<Eigen::VectorXd> witnessPath() const {
    if (witness.empty()) return {};
    std::vector<Eigen::VectorXd> path = {start};
    path.insert(path.end(), witness.begin(), witness.end());
    path.push_back(goal);
    return path;
  }
};

struct Scenario {
  std::string path;
  // FNV-1a 64 of the file's bytes, 16 hex digits: results name the exact problem they ran (--merge
  // refuses shards of a file that has changed since).
  std::string content_hash;
  std::string name;
  std::string description;
  std::shared_ptr<const robots::Robot> robot;
  std::shared_ptr<const Environment> environment;
  std::vector<Query> queries;
  bool queries_listed = false;  // the file gave `queries: [...]`, not a top-level start and goal
  double resolution = 0.01;  // checking resolution in the weighted metric
  Eigen::VectorXd metric_weights;
  bool self_collision = true;
  std::map<std::string, ParameterSet> planner_params;  // by planner name; absent planners get defaults

  ConfigurationSpace makeSpace() const;
  // The parameters of one planner (empty set with the right error prefix when the file has none).
  ParameterSet paramsFor(const std::string& planner) const;
};

// Refuses directories, unreadable paths (with the OS reason) and files over kMaxFileBytes before parsing.
Scenario loadScenario(const std::string& path);
// Same, from YAML text; `source` names it in errors.
Scenario parseScenario(const std::string& yaml_text, const std::string& source);

}  // namespace svmp::cspace
