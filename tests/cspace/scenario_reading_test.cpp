// What a scenario file means, where a probe found the reader taking something silently: divisors of
// pi, aliases that multiply a list, bytes that are not UTF-8, the planner parameters' number syntax,
// a partial flange, and obstacles out of a planar robot's plane, for every shape and rotation.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "cspace/collision_checker.hpp"
#include "cspace/scenario/scenario.hpp"
#include "robots/dh_arm.hpp"
#include "tests/cspace/hostile_inputs.hpp"

namespace svmp::cspace {
namespace {

using namespace hostile;

TEST(ScenarioReadingTest, APiFractionNeedsAFiniteNonZeroDivisor) {
  for (const char* bad : {"pi/inf", "-pi/inf", "pi/1e400", "pi/1e-400", "pi/0", "pi/nan"})
    expectError(with(kPoint, "start: [1, 5]", std::string("start: [1, ") + bad + "]"), {"start[1]", bad});
  const Scenario s = parseScenario(with(kPoint, "start: [1, 5]", "start: [1, 8pi/4]"), "test.yaml");
  EXPECT_DOUBLE_EQ(s.queries[0].start[1], 2 * std::numbers::pi);
}

TEST(ScenarioReadingTest, YamlsInfinityAndNanReadAsInfAndNanDo) {
  for (const char* bad : {"nan", "inf", "-inf", ".nan", ".NaN", ".inf", "-.Inf", "+.INF"})
    expectError(with(kPoint, "start: [1, 5]", std::string("start: [1, ") + bad + "]"),
                {"start[1]", "expected a finite number", bad});
  expectError(with(kPoint, "start: [1, 5]", "start: [1, .nanx]"), {"start[1]", "expected a number", ".nanx"});
}

TEST(ScenarioReadingTest, AnAliasCountsAsTheNodesItNames) {
  // 1,001 aliases of a 1,000-number list: a small file that would expand to a million values.
  std::string list = "[", refs = "[";
  for (int i = 0; i < 1000; ++i) list += std::string(i ? ", " : "") + "1";
  for (int i = 0; i < 1001; ++i) refs += std::string(i ? ", " : "") + "*w";
  const std::string text = with(kPoint, "resolution: 0.05", "resolution: 0.05\nx_list: &w " + list + "]\nx_refs: " + refs + "]");
  expectError(text, {"more than 1000000 YAML nodes", "alias"});
  // A few aliases of small things stay well within the limit (and reach the reader's key check).
  expectError(with(kPoint, "resolution: 0.05", "resolution: 0.05\nx_list: &w [1, 2]\nx_refs: [*w, *w]"),
              {"unknown field 'x_list'"});
}

TEST(ScenarioReadingTest, TextMustBeUtf8) {
  expectError(with(kPoint, "name: two_boxes", "name: two\xff" "boxes"), {"not UTF-8", "line 1, column 10"});
  expectError(with(kPoint, "name: two_boxes", "name: two\xc0\xafz"), {"not UTF-8"});       // overlong '/'
  expectError(with(kPoint, "name: two_boxes", "name: two\xed\xa0\x80z"), {"not UTF-8"});   // a surrogate
  const Scenario s = parseScenario(with(kPoint, "name: two_boxes", "name: zwei_K\xc3\xa4sten"), "test.yaml");
  EXPECT_EQ(s.name, "zwei_K\xc3\xa4sten");
}

TEST(ScenarioReadingTest, PlannerParametersUseTheFilesNumberSyntax) {
  const Scenario s = parseScenario(with(kPoint, "svmp: {sigma: 0.5, k: 10}", "svmp: {sigma: pi/8, k: +10, C: 1e3}"),
                                   "test.yaml");
  const ParameterSet params = s.paramsFor("svmp");
  EXPECT_DOUBLE_EQ(params.getDouble("sigma", 1, 0, 10), std::numbers::pi / 8);
  EXPECT_EQ(params.getInt("k", 1, 1, 100), 10);
  EXPECT_DOUBLE_EQ(params.getDouble("C", 1, 0, 1e6), 1000);
  for (const char* bad : {"0x10", "0x1p-1", "' 0.5'", "1e400", "pi/inf"}) {
    const Scenario b = parseScenario(with(kPoint, "svmp: {sigma: 0.5, k: 10}", std::string("svmp: {sigma: ") + bad + "}"),
                                     "test.yaml");
    try {
      b.paramsFor("svmp").getDouble("sigma", 1, 0, 1e6);
      ADD_FAILURE() << bad << " was read as a number";
    } catch (const ScenarioError& e) {
      EXPECT_NE(std::string(e.what()).find("planners.svmp.sigma"), std::string::npos) << e.what();
    }
  }
  for (const char* bad : {"0x10", "' 7'", "7.5", "99999999999999999999"}) {
    const Scenario b = parseScenario(with(kPoint, "svmp: {sigma: 0.5, k: 10}", std::string("svmp: {k: ") + bad + "}"),
                                     "test.yaml");
    EXPECT_THROW(b.paramsFor("svmp").getInt("k", 1, 1, 100), ScenarioError) << bad;
  }
}

TEST(ScenarioReadingTest, APartialFlangeKeepsThePresetsOtherValues) {
  const std::string crs = R"(robot: {type: dh_arm, preset: crs_f3, joints: 3}
start: [0, 0, 0]
goal: [0.5, 0, 0]
resolution: 0.02
)";
  const auto preset = std::dynamic_pointer_cast<const robots::DhArm>(parseScenario(crs, "test.yaml").robot);
  const std::string partial = with(crs, "joints: 3}", "joints: 3, flange: {d: 0.3}}");
  const auto changed = std::dynamic_pointer_cast<const robots::DhArm>(parseScenario(partial, "test.yaml").robot);
  ASSERT_TRUE(preset && changed);
  EXPECT_EQ(changed->spec().flange.a, preset->spec().flange.a);
  EXPECT_EQ(changed->spec().flange.alpha, preset->spec().flange.alpha);
  EXPECT_EQ(changed->spec().flange.d, 0.3);
  EXPECT_NE(preset->spec().flange.alpha, 0.0) << "test premise: the preset's flange is rotated";
}

// A planar robot moves in z = 0: an obstacle is refused exactly when no point of it lies within the
// robot's own height of that plane, whatever its shape and rotation.
TEST(ScenarioReadingTest, PlanarObstaclesMustReachTheRobotsPlane) {
  const std::string point = R"(robot: {type: point, bounds: {lower: [0, 0], upper: [10, 10]}}
obstacles:
  - OBSTACLE
start: [1, 1]
goal: [9, 1]
resolution: 0.05
)";
  auto at = [&](const std::string& obstacle) { return with(point, "OBSTACLE", obstacle); };
  // Off the plane: refused, with the spans named.
  for (const char* off : {"{shape: sphere, radius: 1, position: [5, 5, 3]}",
                          "{shape: capsule, radius: 0.5, length: 2, position: [5, 5, 2]}",
                          "{shape: cylinder, radius: 1, length: 1, position: [5, 5, 1.6], rpy: [pi/2, 0, 0]}",
                          "{shape: box, size: [2, 2, 8], position: [5, 5, 3], rpy: [pi/2, 0, 0]}"})
    expectError(at(off), {"obstacles[0].position", "does not reach it", "spans z in"});
  // Reaching it: accepted, and a configuration under the obstacle's centre collides.
  for (const char* on : {"{shape: box, size: [2, 2, 0.2], position: [5, 5, 0.5], rpy: [pi/2, 0, 0]}",
                         "{shape: cylinder, radius: 1, length: 1, position: [5, 5, 0.9], rpy: [pi/2, 0, 0]}",
                         "{shape: capsule, radius: 0.5, length: 2, position: [5, 5, 1.4]}"}) {
    const Scenario s = parseScenario(at(on), "test.yaml");
    const CollisionChecker checker(s.robot, s.environment, s.self_collision);
    EXPECT_EQ(checker.check(Eigen::Vector2d(5, 5)), 1) << on;
  }
  // A planar arm's links have height: a box within it collides with the arm and is accepted.
  const std::string arm = R"(robot: {type: planar_arm, lengths: [1, 1], widths: 0.2}
obstacles:
  - {shape: box, size: [0.2, 0.2, 0.1], position: [1.5, 0, 0.1]}
start: [0, 0]
goal: [1, 1]
resolution: 0.01
)";
  const Scenario s = parseScenario(arm, "test.yaml");
  const CollisionChecker checker(s.robot, s.environment, s.self_collision);
  EXPECT_EQ(checker.check(Eigen::Vector2d(0, 0)), 1);
  expectError(with(arm, "position: [1.5, 0, 0.1]", "position: [1.5, 0, 0.2]"), {"does not reach it"});
}

// rpy is roll about x, then pitch about y, then yaw about z, all about the fixed axes (URDF's
// convention): R = Rz(yaw) Ry(pitch) Rx(roll). A box 2 x 1 x 0.05 turned by all three: its long
// axis points along R x = (cos y cos p, sin y cos p, -sin p), its thin one along R z, derived by hand.
TEST(ScenarioReadingTest, RollPitchYawTurnAboutTheFixedAxesInThatOrder) {
  const double roll = 0.3, pitch = -0.4, yaw = 1.1;
  const std::string text = R"(robot: {type: point, bounds: {lower: [-5, -5, -5], upper: [5, 5, 5]}}
obstacles:
  - {shape: box, size: [2, 1, 0.05], position: [0, 0, 0], rpy: [0.3, -0.4, 1.1]}
start: [4, 4, 4]
goal: [-4, 4, 4]
resolution: 0.01
)";
  const Scenario s = parseScenario(text, "test.yaml");
  const CollisionChecker checker(s.robot, s.environment, s.self_collision);
  const Eigen::Vector3d long_axis(std::cos(yaw) * std::cos(pitch), std::sin(yaw) * std::cos(pitch), -std::sin(pitch));
  const Eigen::Vector3d thin_axis(std::cos(yaw) * std::sin(pitch) * std::cos(roll) + std::sin(yaw) * std::sin(roll),
                                  std::sin(yaw) * std::sin(pitch) * std::cos(roll) - std::cos(yaw) * std::sin(roll),
                                  std::cos(pitch) * std::cos(roll));
  EXPECT_EQ(checker.check(Eigen::Vector3d(0.95 * long_axis)), 1);
  EXPECT_EQ(checker.check(Eigen::Vector3d(-0.95 * long_axis)), 1);
  EXPECT_EQ(checker.check(Eigen::Vector3d(0.02 * thin_axis)), 1);
  EXPECT_EQ(checker.check(Eigen::Vector3d(0.04 * thin_axis)), kFree);
  // The other orders put the long axis elsewhere: 1.05 along it is past the box's end.
  EXPECT_EQ(checker.check(Eigen::Vector3d(1.05 * long_axis)), kFree);
  const Eigen::Matrix3d other = (Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()) *
                                 Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
                                 Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ())).toRotationMatrix();
  EXPECT_EQ(checker.check(Eigen::Vector3d(0.95 * (other * Eigen::Vector3d::UnitX()))), kFree);
}

}  // namespace
}  // namespace svmp::cspace
