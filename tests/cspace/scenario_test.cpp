// Scenario parsing from text: valid files for each robot type, and errors that name field and value.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "cspace/scenario/scenario.hpp"
#include "robots/dh_arm.hpp"
#include "robots/planar_arm.hpp"
#include "tests/cspace/hostile_inputs.hpp"

namespace svmp::cspace {
namespace {

constexpr double kPi = std::numbers::pi;

using hostile::errorOf;
using hostile::kPoint;

// Replaces the first occurrence of `from` in the valid point scenario.
std::string pointScenarioWith(const std::string& from, const std::string& to) { return hostile::with(kPoint, from, to); }

void expectErrorNames(const std::string& text, const std::vector<std::string>& parts) {
  const std::string message = errorOf(text);
  EXPECT_NE(message.find("test.yaml"), std::string::npos) << message;
  for (const auto& part : parts) EXPECT_NE(message.find(part), std::string::npos) << message << "\nlacks: " << part;
}

TEST(ScenarioTest, ParsesAPointRobotScenario) {
  const Scenario s = parseScenario(kPoint, "test.yaml");
  EXPECT_EQ(s.name, "two_boxes");
  EXPECT_EQ(s.robot->name(), "point2d");
  ASSERT_EQ(s.environment->size(), 2);
  const Obstacle& lower = s.environment->byId(1);
  EXPECT_EQ(lower.name, "lower");
  EXPECT_EQ(lower.shape.dims, Eigen::Vector3d(4, 6, 1));
  EXPECT_EQ(lower.shape.pose.translation(), Eigen::Vector3d(5, 3, 0));
  EXPECT_TRUE(s.environment->byId(2).is_virtual);
  EXPECT_EQ(s.environment->byId(2).weight, 2.0);
  EXPECT_EQ(s.environment->numReal(), 1);
  ASSERT_EQ(s.queries.size(), 1u);
  EXPECT_EQ(s.queries[0].start, Eigen::VectorXd(Eigen::Vector2d(1, 5)));
  ASSERT_EQ(s.queries[0].witness.size(), 2u);
  EXPECT_EQ(s.resolution, 0.05);
  EXPECT_EQ(s.metric_weights, Eigen::VectorXd(Eigen::Vector2d(1, 2)));
  EXPECT_EQ(s.makeSpace().dim(), 2);
  const ParameterSet svmp = s.paramsFor("svmp");
  EXPECT_EQ(svmp.getDouble("sigma", 1.0), 0.5);
  EXPECT_EQ(svmp.getInt("k", 5), 10);
  svmp.requireAllUsed();
  EXPECT_EQ(s.paramsFor("prm").getInt("k", 7), 7);  // absent planner: defaults
}

TEST(ScenarioTest, ParsesAPlanarArmWithAnglesInPi) {
  const Scenario s = parseScenario(R"(
robot:
  type: planar_arm
  lengths: [1, 0.5]
  widths: 0.1
  limits: {lower: [-pi, -pi/2], upper: [pi, 0.5pi]}
  base: [0.5, 0]
obstacles: [{shape: cylinder, radius: 0.2, length: 1, position: [2, 2, 0]}]
queries:
  - {start: [0, 0], goal: [1, -pi/4]}
  - {start: [0.1, 0], goal: [2, 1], witness: [[1, 0.5]]}
resolution: 0.01
)", "arm.yaml");
  const auto& arm = dynamic_cast<const robots::PlanarArm&>(*s.robot);
  EXPECT_EQ(arm.lengths(), (std::vector<double>{1, 0.5}));
  EXPECT_EQ(arm.widths(), (std::vector<double>{0.1, 0.1}));
  EXPECT_NEAR(arm.lowerLimits()[1], -kPi / 2, 1e-15);
  EXPECT_NEAR(arm.upperLimits()[1], kPi / 2, 1e-15);
  EXPECT_EQ(arm.base(), Eigen::Vector2d(0.5, 0));
  ASSERT_EQ(s.queries.size(), 2u);
  EXPECT_NEAR(s.queries[0].goal[1], -kPi / 4, 1e-15);
  EXPECT_TRUE(s.queries[0].witness.empty());
  EXPECT_EQ(s.queries[1].witness.size(), 1u);
  EXPECT_EQ(s.metric_weights, Eigen::VectorXd::Ones(2));
}

TEST(ScenarioTest, ParsesDhPresetsAndTables) {
  const Scenario crs = parseScenario(R"(
robot: {type: dh_arm, preset: crs_f3, joints: 3}
start: [0, 0, 0]
goal: [1, 0.5, -0.5]
resolution: 0.02
self_collision: false
)", "crs.yaml");
  EXPECT_EQ(crs.robot->name(), "crs_f3_3dof");
  EXPECT_FALSE(crs.self_collision);
  const Scenario panda = parseScenario(R"(
robot: {type: dh_arm, preset: panda}
start: [0, -0.785, 0, -2.356, 0, 1.571, 0.785]
goal: [0.5, -0.785, 0, -2.356, 0, 1.571, 0.785]
resolution: 0.02
)", "panda.yaml");
  EXPECT_EQ(panda.robot->dof(), 7);
  const Scenario table = parseScenario(R"(
robot:
  type: dh_arm
  name: two_link
  dh: [{d: 0.3}, {alpha: pi/2, a: 0.2}]
  limits: {lower: [-1, -1], upper: [1, 1]}
  flange: {a: 0.25}
  tool: [{shape: box, size: [0.1, 0.1, 0.1]}]
start: [0, 0]
goal: [0.5, 0.5]
resolution: 0.02
)", "table.yaml");
  const auto& arm = dynamic_cast<const robots::DhArm&>(*table.robot);
  EXPECT_EQ(arm.name(), "two_link");
  EXPECT_NEAR(arm.spec().rows[1].alpha, kPi / 2, 1e-15);
  // Frame 2 at (0, 0, 0.3) + 0.2 x; flange 0.25 further along frame 2's x (= world x at q = 0).
  EXPECT_LT((arm.flangePose(Eigen::Vector2d(0, 0)).translation() - Eigen::Vector3d(0.45, 0, 0.3)).norm(), 1e-12);
}

TEST(ScenarioTest, MalformedInputsNameFieldAndValue) {
  expectErrorNames(pointScenarioWith("robot: {type: point, bounds: {lower: [0, 0], upper: [10, 10]}}", ""),
                   {"'robot'", "required"});
  expectErrorNames(pointScenarioWith("type: point", "type: hexapod"), {"robot.type", "hexapod"});
  expectErrorNames(pointScenarioWith("size: [4, 6, 1]", "size: [4, -6, 1]"), {"obstacles[0].size", "-6"});
  expectErrorNames(pointScenarioWith("radius: 0.5", "radius: -0.5"), {"obstacles[1].radius", "-0.5"});
  expectErrorNames(pointScenarioWith("resolution: 0.05", "resolution: .nan"), {"resolution", ".nan"});
  expectErrorNames(pointScenarioWith("start: [1, 5]", "start: [1, .nan]"), {"start[1]", ".nan"});
  expectErrorNames(pointScenarioWith("goal: [9, 5]", "goal: [9, 5, 1]"), {"goal", "expected 2 numbers", "[9, 5, 1]"});
  expectErrorNames(pointScenarioWith("start: [1, 5]", "start: [11, 5]"), {"start", "11", "outside the joint limits"});
  // A value a rounding away from its limit is named with every digit, and the joint with it.
  expectErrorNames(pointScenarioWith("start: [1, 5]", "start: [1, 10.0000000001]"),
                   {"start", "joint 2 10.0000000001 not in [0, 10]"});
  expectErrorNames(pointScenarioWith("witness: [[2.5, 6.15], [7.5, 6.15]]", "witness: [[2.5, 6.15], [-1, 6.15]]"),
                   {"witness[1]", "-1"});
  expectErrorNames(pointScenarioWith("witness: [[2.5, 6.15], [7.5, 6.15]]", "witness: []"), {"witness", "an empty list"});
  expectErrorNames(pointScenarioWith("resolution: 0.05", "resolution: 0.05\nresolutoin: 0.1"), {"resolutoin", "unknown field"});
  expectErrorNames(pointScenarioWith("start: [1, 5]", "start: [1, 5"), {"YAML syntax error"});
  expectErrorNames(pointScenarioWith("metric_weights: [1, 2]", "metric_weights: [1, 0]"), {"metric_weights[1]", "0"});
  expectErrorNames(pointScenarioWith("shape: sphere", "shape: torus"), {"obstacles[1].shape", "torus"});
  expectErrorNames(pointScenarioWith("virtual: true", "virtual: maybe"), {"obstacles[1].virtual", "maybe"});
  expectErrorNames(pointScenarioWith("goal: [9, 5]", "goal: [9, five]"), {"goal[1]", "five"});
  expectErrorNames(pointScenarioWith("upper: [10, 10]", "upper: [10, -1]"), {"robot.bounds", "joint 2"});
  expectErrorNames(pointScenarioWith("sigma: 0.5", "sigma: [0.5]"), {"planners.svmp.sigma"});
  // A DH arm whose segments all have zero length has nothing that could collide: its clearance
  // read "inf" inside a sphere that engulfed it.
  expectErrorNames("robot: {type: dh_arm, dh: [{a: 0, alpha: 0, d: 0}, {a: 0, alpha: pi/2, d: 0}], "
                   "link_radius: [0.1, 0.1], limits: {lower: [-3, -3], upper: [3, 3]}}\n"
                   "start: [-1, 0]\ngoal: [1, 0]\nresolution: 0.01\n",
                   {"robot", "no moving collision shape"});
  // The same with only the base column (row 1) long: it never moves, so the robot still has none.
  expectErrorNames("robot: {type: dh_arm, dh: [{a: 0.3, alpha: 0.5, d: 0.2}, {a: 0, alpha: pi/2, d: 0}], "
                   "link_radius: [0.1, 0.1], limits: {lower: [-3, -3], upper: [3, 3]}}\n"
                   "start: [-1, 0]\ngoal: [1, 0]\nresolution: 0.01\n",
                   {"robot", "no moving collision shape", "after joint 1"});
}

TEST(ScenarioTest, WrongNodeKindsAreScenarioErrors) {
  // yaml-cpp throws its own exceptions when a scalar is indexed like a mapping; the loader must turn
  // them into ScenarioError naming the field.
  expectErrorNames(pointScenarioWith("robot: {type: point, bounds: {lower: [0, 0], upper: [10, 10]}}", "robot: point"),
                   {"robot"});
  expectErrorNames(pointScenarioWith("  - {name: lower, shape: box, size: [4, 6, 1], position: [5, 3, 0]}", "  - 3"),
                   {"obstacles[0]"});
  expectErrorNames(pointScenarioWith("bounds: {lower: [0, 0], upper: [10, 10]}", "bounds: 10"), {"robot.bounds"});
  expectErrorNames("[1, 2]", {"top level"});
}

TEST(ScenarioTest, NegativePiMultiplesParse) {
  const Scenario s = parseScenario(R"(
robot: {type: planar_arm, lengths: [1], widths: [0.1], limits: {lower: [-pi/2], upper: [2pi/3]}}
start: [-pi/4]
goal: [-0.25pi]
resolution: 0.01
)", "pi.yaml");
  EXPECT_NEAR(s.robot->lowerLimits()[0], -kPi / 2, 1e-15);
  EXPECT_NEAR(s.robot->upperLimits()[0], 2 * kPi / 3, 1e-15);
  EXPECT_NEAR(s.queries[0].start[0], -kPi / 4, 1e-15);
  EXPECT_NEAR(s.queries[0].goal[0], -kPi / 4, 1e-15);
  expectErrorNames(pointScenarioWith("start: [1, 5]", "start: [1, pi/2x]"), {"start[1]", "pi/2x"});
  expectErrorNames(pointScenarioWith("start: [1, 5]", "start: [1, pi/0]"), {"start[1]", "pi/0"});
}

TEST(ParameterSetTest, BoundsParsingAndUnusedKeys) {
  ParameterSet p("file.yaml", "planners.svmp.",
                 {{"sigma", "0.5"}, {"k", "10"}, {"bad", "1.5x"}, {"big", "1e400"}, {"flag", "true"}});
  EXPECT_EQ(p.getDouble("sigma", 1, 0, 1), 0.5);
  EXPECT_EQ(p.getDouble("absent", 3.5), 3.5);
  EXPECT_EQ(p.getInt("k", 1, 1, 100), 10);
  EXPECT_TRUE(p.getBool("flag", false));
  try {
    p.getDouble("sigma", 1, 0.6, 1);
    FAIL() << "out of bounds accepted";
  } catch (const ScenarioError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("file.yaml"), std::string::npos) << m;
    EXPECT_NE(m.find("planners.svmp.sigma"), std::string::npos) << m;
    EXPECT_NE(m.find("0.5"), std::string::npos) << m;
  }
  EXPECT_THROW(p.getInt("k", 1, 11, 100), ScenarioError);
  EXPECT_THROW(p.getInt("sigma", 1), ScenarioError);  // "0.5" is not an integer
  EXPECT_THROW(p.getDouble("bad", 1), ScenarioError);
  EXPECT_THROW(p.getDouble("big", 1), ScenarioError);
  EXPECT_THROW(p.getString("flag", "", {"a", "b"}), ScenarioError);
  ParameterSet typo("file.yaml", "planners.prm.", {{"milestones", "100"}, {"kk", "3"}});
  typo.getInt("milestones", 1);
  try {
    typo.requireAllUsed();
    FAIL() << "unused key accepted";
  } catch (const ScenarioError& e) {
    EXPECT_NE(std::string(e.what()).find("planners.prm.kk"), std::string::npos) << e.what();
  }
  typo.getInt("kk", 1);
  EXPECT_NO_THROW(typo.requireAllUsed());
}

}  // namespace
}  // namespace svmp::cspace
