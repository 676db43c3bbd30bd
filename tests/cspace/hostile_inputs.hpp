#pragma once
// Base scenarios and error helpers shared by the scenario tests that feed the reader bad input.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "cspace/scenario/scenario.hpp"

namespace svmp::cspace::hostile {

inline const char* const kPoint = R"(name: two_boxes
robot: {type: point, bounds: {lower: [0, 0], upper: [10, 10]}}
obstacles:
  - {name: lower, shape: box, size: [4, 6, 1], position: [5, 3, 0]}
  - {name: ball, shape: sphere, radius: 0.5, position: [1, 1], virtual: true, weight: 2}
start: [1, 5]
goal: [9, 5]
witness: [[2.5, 6.15], [7.5, 6.15]]
resolution: 0.05
metric_weights: [1, 2]
planners:
  svmp: {sigma: 0.5, k: 10}
)";

inline const char* const kPlanar = R"(robot:
  type: planar_arm
  lengths: [1, 0.5]
  widths: 0.1
  limits: {lower: [-pi, -pi/2], upper: [pi, 0.5pi]}
  base: [0.5, 0]
start: [0, 0]
goal: [1, 0.5]
resolution: 0.01
)";

inline const char* const kDh = R"(robot:
  type: dh_arm
  name: two_link
  dh: [{d: 0.3}, {alpha: pi/2, a: 0.2}]
  limits: {lower: [-1, -1], upper: [1, 1]}
  link_radius: [0.05, 0.05]
  flange: {a: 0.25}
  base: {position: [0, 0, 0.1], rpy: [0, 0, 0]}
  tool: [{shape: box, size: [0.1, 0.1, 0.1], position: [0, 0, 0.05]}]
  tool_tip: [0, 0, 0.1]
start: [0, 0]
goal: [0.5, 0.5]
resolution: 0.02
)";

inline const char* const kPanda = R"(robot: {type: dh_arm, preset: panda}
start: [0, -0.785, 0, -2.356, 0, 1.571, 0.785]
goal: [0.5, -0.785, 0, -2.356, 0, 1.571, 0.785]
resolution: 0.02
)";

inline std::string with(const std::string& base, const std::string& from, const std::string& to) {
  std::string text = base;
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "test bug: '" << from << "' not in the base scenario";
  return at == std::string::npos ? text : text.replace(at, from.size(), to);
}

// The ScenarioError message for `text`; a test failure when nothing or something else is thrown.
inline std::string errorOf(const std::string& text) {
  try {
    parseScenario(text, "test.yaml");
  } catch (const ScenarioError& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected ScenarioError, got another exception: " << e.what();
    return "";
  }
  ADD_FAILURE() << "expected ScenarioError for:\n" << text.substr(0, 2000);
  return "";
}

inline void expectError(const std::string& text, const std::vector<std::string>& parts,
                 const std::vector<std::string>& absent = {}) {
  const std::string message = errorOf(text);
  EXPECT_EQ(message.rfind("test.yaml: ", 0), 0u) << message;
  for (const auto& part : parts) EXPECT_NE(message.find(part), std::string::npos) << message << "\n  lacks: " << part;
  for (const auto& part : absent) EXPECT_EQ(message.find(part), std::string::npos) << message << "\n  has: " << part;
  EXPECT_LT(message.size(), 1500u) << "overlong message";
}

inline std::string fileError(const std::string& path) {
  try {
    loadScenario(path);
  } catch (const ScenarioError& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected ScenarioError, got another exception: " << e.what();
    return "";
  }
  ADD_FAILURE() << "expected ScenarioError for " << path;
  return "";
}

}  // namespace svmp::cspace::hostile
