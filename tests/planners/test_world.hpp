#pragma once
// Shared fixtures of the planners tests: a scenario parsed from inline YAML with its space, checker,
// local planner and planning context (which holds references, so the world lives on the heap), and an
// independent re-check of a path at a quarter of the checking resolution.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <initializer_list>
#include <memory>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "cspace/certified_motion_validator.hpp"
#include "cspace/collision_checker.hpp"
#include "cspace/motion_validator.hpp"
#include "cspace/scenario/scenario.hpp"
#include "planners/planner_registry.hpp"
#include "planners/roadmap.hpp"

namespace svmp::planners::test {

struct World {
  cspace::Scenario scenario;
  cspace::ConfigurationSpace space;
  cspace::CollisionChecker checker;
  cspace::DiscreteMotionValidator validator;
  cspace::CertifiedMotionValidator certifier;
  PlanningContext context;  // certifier unset; certify() sets it (as the driver does)

  World(const std::string& yaml, int threads)
      : scenario(cspace::parseScenario(yaml, "test.yaml")),
        space(scenario.makeSpace()),
        checker(scenario.robot, scenario.environment, scenario.self_collision),
        validator(checker, space, scenario.resolution),
        certifier(checker, space, scenario.resolution),
        context{space, checker, validator, threads} {}
  void certify() { context.certifier = &certifier; }
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  const cspace::Query& query() const { return scenario.queries.front(); }
  std::unique_ptr<Planner> planner(const std::string& name) const {
    return makePlanner(name, context, scenario.paramsFor(name));
  }
};

// The text of bench/scenarios/NAME (SVMP_SOURCE_DIR is set for every planners test).
inline std::string readScenario(const std::string& name) {
  const std::string path = std::string(SVMP_SOURCE_DIR) + "/bench/scenarios/" + name;
  std::ifstream in(path);
  EXPECT_TRUE(in.good()) << path;
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

inline std::unique_ptr<World> makeWorld(const std::string& yaml, int threads = 1) {
  return std::make_unique<World>(yaml, threads);
}

// A roadmap of planar nodes (x, y) and edges between them costing their distance in `space`, marked
// checked or not.
inline Roadmap planarRoadmap(const cspace::ConfigurationSpace& space,
                             std::initializer_list<std::pair<double, double>> nodes,
                             std::initializer_list<std::pair<int, int>> edges, bool checked) {
  Roadmap roadmap;
  for (auto [x, y] : nodes) roadmap.addNode(Eigen::Vector2d(x, y));
  for (auto [a, b] : edges) roadmap.addEdge(a, b, space.distance(roadmap.node(a), roadmap.node(b)), checked);
  return roadmap;
}

// A point robot in the unit square; a wall x in [0.4, 0.6] split into two obstacles by a horizontal gap
// at y = 0.5 of usable width `gap` (as bench/scenarios/gap_*.yaml).
inline std::string gapScenario(double gap, const std::string& planners, const std::string& extra = "") {
  const double half = 0.5 * gap + 1e-6;  // robot radius 1e-6
  const double lower_top = 0.5 - half, upper_bottom = 0.5 + half;
  const double lower_size = lower_top + 0.1, upper_size = 1.1 - upper_bottom;
  char buf[2048];
  std::snprintf(buf, sizeof(buf),
                "name: gap\n"
                "robot: {type: point, bounds: {lower: [0, 0], upper: [1, 1]}}\n"
                "obstacles:\n"
                "  - {name: wall_lower, shape: box, size: [0.2, %.9f, 1.0], position: [0.5, %.9f, 0]}\n"
                "  - {name: wall_upper, shape: box, size: [0.2, %.9f, 1.0], position: [0.5, %.9f, 0]}\n"
                "start: [0.1, 0.1]\n"
                "goal: [0.9, 0.9]\n"
                "resolution: 0.002\n",
                lower_size, lower_top - 0.5 * lower_size, upper_size, upper_bottom + 0.5 * upper_size);
  return std::string(buf) + extra + "planners:\n" + planners;
}

// Segment a-b re-checked by an independent checker at 1/4 of the resolution, end points included.
// `allowed_run` > 0 tolerates colliding stretches shorter than that (metric length between the free
// configurations around them): a validator checking at spacing `resolution` can only promise that no
// stretch longer than the resolution collides (it may clip a corner between two checks).
inline ::testing::AssertionResult segmentIsValid(const World& w, const Eigen::VectorXd& a, const Eigen::VectorXd& b,
                                                 double allowed_run = 0) {
  const cspace::CollisionChecker independent(w.scenario.robot, w.scenario.environment, w.scenario.self_collision);
  const double length = w.space.distance(a, b);
  const int steps = std::max(1, static_cast<int>(std::ceil(length / (0.25 * w.scenario.resolution))));
  int last_free = -1;
  for (int s = 0; s <= steps; ++s) {
    const Eigen::VectorXd q = a + (static_cast<double>(s) / steps) * (b - a);
    const int hit = independent.check(q);
    if (hit == cspace::kFree) {
      last_free = s;
      continue;
    }
    // The colliding stretch reaches at least from the last free point to the next one.
    const double run = (s + 1 - last_free) * length / steps;
    if (s == 0 || s == steps || run > allowed_run)
      return ::testing::AssertionFailure() << "hits " << hit << " at " << q.transpose() << " (colliding stretch "
                                           << run << " > allowed " << allowed_run << ")";
  }
  return ::testing::AssertionSuccess();
}

// The path joins the query's start and goal, and every segment passes segmentIsValid.
inline ::testing::AssertionResult pathIsValid(const World& w, const std::vector<Eigen::VectorXd>& path,
                                              const cspace::Query& query, double allowed_run = 0) {
  if (path.size() < 2) return ::testing::AssertionFailure() << "path has " << path.size() << " configurations";
  if ((path.front() - query.start).norm() > 1e-9)
    return ::testing::AssertionFailure() << "path starts at " << path.front().transpose();
  if ((path.back() - query.goal).norm() > 1e-9)
    return ::testing::AssertionFailure() << "path ends at " << path.back().transpose();
  for (size_t i = 0; i + 1 < path.size(); ++i)
    if (auto valid = segmentIsValid(w, path[i], path[i + 1], allowed_run); !valid) return valid << " (segment " << i << ")";
  return ::testing::AssertionSuccess();
}
// The same for the scenario's own query.
inline ::testing::AssertionResult pathIsValid(const World& w, const std::vector<Eigen::VectorXd>& path,
                                              double allowed_run = 0) {
  return pathIsValid(w, path, w.query(), allowed_run);
}

}  // namespace svmp::planners::test
