// Obstacle sampling (thesis Algorithm 1): labels, tree sizes, boundary samples, roots, determinism.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "planners/obstacle_sampler.hpp"
#include "test_world.hpp"

namespace svmp::planners {
namespace {

using test::makeWorld;

// Three obstacles: two boxes and a sphere; the sphere's root comes from the scenario.
const char* kThreeObstacles =
    "robot: {type: point, bounds: {lower: [0, 0], upper: [1, 1]}}\n"
    "obstacles:\n"
    "  - {name: left, shape: box, size: [0.2, 0.6, 1.0], position: [0.2, 0.5, 0]}\n"
    "  - {name: right, shape: box, size: [0.2, 0.6, 1.0], position: [0.8, 0.5, 0]}\n"
    "  - {name: ball, shape: sphere, radius: 0.1, position: [0.5, 0.85, 0], sample: [0.53, 0.82]}\n"
    "start: [0.5, 0.1]\n"
    "goal: [0.5, 0.5]\n"
    "resolution: 0.01\n"
    "metric_weights: [1.0, 2.0]\n";

// sampleObstacles on one thread, and the collision checks it made.
struct CountedSamples {
  planners::ObstacleSamples samples;
  std::uint64_t checks;
};
CountedSamples sampleCountingChecks(const test::World& w, const planners::ObstacleSamplerOptions& opt,
                                    std::uint64_t seed) {
  const std::uint64_t before = w.checker.collisionChecks();
  planners::ObstacleSamples s = planners::sampleObstacles(w.checker, w.space, opt, seed, 1);
  return {std::move(s), w.checker.collisionChecks() - before};
}

// Trees of 30 samples a step of 0.05 apart: the arm tests' sampling.
planners::ObstacleSamplerOptions smallArmTrees() {
  planners::ObstacleSamplerOptions opt;
  opt.step = 0.05;
  opt.samples_per_tree = 30;
  return opt;
}

// Every sample hits the obstacle it is labelled with (its first miss named).
::testing::AssertionResult everySampleHitsItsObstacle(const test::World& w, const planners::ObstacleSamples& s) {
  for (int i = 0; i < s.size(); ++i)
    if (!w.checker.hits(s.points.col(i), s.labels[i]))
      return ::testing::AssertionFailure() << "sample " << i << " at " << s.points.col(i).transpose()
                                           << " does not hit " << s.labels[i];
  return ::testing::AssertionSuccess();
}

planners::ObstacleSamplerOptions samplerOptions() {
  planners::ObstacleSamplerOptions o;
  o.step = 0.04;
  o.samples_per_tree = 150;
  return o;
}

TEST(ObstacleSampler, SamplesHitTheirObstacleAndTreesAreFull) {
  auto w = makeWorld(kThreeObstacles);
  auto opt = samplerOptions();
  // Algorithm 1's N nodes per tree: the ball (3% of the space) stalls at 20 nodes under the
  // default stall limit of 2 x max(20, nodes) idle expansions, since few targets fall near it.
  opt.max_idle_factor = 50;
  opt.max_expansions_per_node = 0;
  const auto s = planners::sampleObstacles(w->checker, w->space, opt, 21, 1);
  EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
  ASSERT_EQ(s.tree_sizes.size(), 3u);
  for (int size : s.tree_sizes) EXPECT_EQ(size, opt.samples_per_tree);
  ASSERT_EQ(s.size(), 3 * opt.samples_per_tree);
  ASSERT_EQ(s.points.cols(), s.size());
  ASSERT_EQ(s.boundary.size(), s.labels.size());
  std::vector<int> per_label(4, 0), boundary_per_label(4, 0);
  for (int i = 0; i < s.size(); ++i) {
    ASSERT_GE(s.labels[i], 1);
    ASSERT_LE(s.labels[i], 3);
    ++per_label[s.labels[i]];
    boundary_per_label[s.labels[i]] += s.boundary[i];
    EXPECT_TRUE(w->space.contains(s.points.col(i)));
  }
  EXPECT_TRUE(everySampleHitsItsObstacle(*w, s));
  for (int id = 1; id <= 3; ++id) {
    EXPECT_EQ(per_label[id], opt.samples_per_tree);
    EXPECT_GT(boundary_per_label[id], 0) << "obstacle " << id << " has no boundary sample";
  }
  EXPECT_EQ(s.numBoundary(), boundary_per_label[1] + boundary_per_label[2] + boundary_per_label[3]);
}

// A box only a few steps wide holds fewer than N samples a step apart: its tree stops after 2 N
// expansions in a row that add nothing, says so, and spends far fewer checks than the 50 N expansion
// limit would.
TEST(ObstacleSampler, AFullTreeStopsGrowing) {
  auto w = makeWorld(
      "robot: {type: point, bounds: {lower: [0, 0], upper: [10, 10]}}\n"
      "obstacles:\n"
      "  - {name: pebble, shape: box, size: [0.3, 0.3, 1.0], position: [5, 5, 0], sample: [5, 5]}\n"
      "start: [1, 1]\n"
      "goal: [9, 9]\n"
      "resolution: 0.01\n");
  planners::ObstacleSamplerOptions opt;
  opt.step = 0.05;
  opt.samples_per_tree = 200;
  const auto [s, checks] = sampleCountingChecks(*w, opt, 3);
  ASSERT_EQ(s.tree_sizes.size(), 1u);
  EXPECT_LT(s.tree_sizes[0], opt.samples_per_tree);
  EXPECT_GT(s.tree_sizes[0], 10) << s.warnings.front();
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_NE(s.warnings[0].find("added nothing"), std::string::npos) << s.warnings[0];
  // Each idle expansion is one check; the limit would be 50 x 200 of them.
  EXPECT_LT(checks, 10u * static_cast<std::uint64_t>(opt.samples_per_tree) + 100u * s.tree_sizes[0]);
  EXPECT_TRUE(everySampleHitsItsObstacle(*w, s));
}

// A wall a third of a step thick, in a space where most uniform targets lie across it: most
// expansions leave it, and each new boundary node restarts the idle count, so without the per-node
// limit the tree goes on at about 35 checks a node (10.5k for 300). With it the tree stops, says
// why, and has spent at most max_expansions_per_node expansions a node.
TEST(ObstacleSampler, AThinTreeStopsAtItsExpansionsPerNode) {
  auto w = makeWorld(
      "robot: {type: point, bounds: {lower: [0, 0], upper: [2, 10]}}\n"
      "obstacles:\n"
      "  - {name: wall, shape: box, size: [0.03, 8, 1.0], position: [1, 5, 0], sample: [1, 5]}\n"
      "start: [0.5, 1]\n"
      "goal: [1.5, 9]\n"
      "resolution: 0.005\n");
  planners::ObstacleSamplerOptions opt;
  opt.step = 0.1;
  opt.samples_per_tree = 300;
  const auto [thin, thin_checks] = sampleCountingChecks(*w, opt, 5);
  ASSERT_EQ(thin.warnings.size(), 1u);
  EXPECT_NE(thin.warnings[0].find("thin region"), std::string::npos) << thin.warnings[0];
  EXPECT_TRUE(everySampleHitsItsObstacle(*w, thin));
  const int nodes = thin.tree_sizes[0];
  EXPECT_GT(nodes, 20);
  // Expansions (one check each) plus a bisection (log2(step / (step / 256)) = 8 checks) per
  // boundary node.
  EXPECT_LE(thin_checks, static_cast<std::uint64_t>(opt.max_expansions_per_node * nodes + 1 + 8 * thin.numBoundary()));
  opt.max_expansions_per_node = 0;
  const auto [full, full_checks] = sampleCountingChecks(*w, opt, 5);
  EXPECT_GT(full.tree_sizes[0], nodes);
  EXPECT_GT(full_checks, 2 * thin_checks);
}

// A boundary sample faces free space (thesis Algorithm 1: q_expansion is a boundary sample when q_new
// is free), not another obstacle: two boxes overlapping over x in [0.3, 0.5] give none inside their
// overlap, where a step into the other box used to mark 28 of them.
void expectBoundarySamplesFaceFreeSpace(const std::string& scene) {
  auto w = makeWorld(scene);
  const auto opt = samplerOptions();
  const auto s = planners::sampleObstacles(w->checker, w->space, opt, 22, 1);
  const Eigen::VectorXd& scale = w->space.metricScale();
  int checked = 0;
  for (int i = 0; i < s.size(); ++i) {
    if (!s.boundary[i]) continue;
    ++checked;
    const Eigen::VectorXd q = s.points.col(i);
    bool found = false;
    // Probe directions on circles of metric radius <= step (the step that left the obstacle had
    // metric length <= step and ended inside the bounds).
    for (double radius : {1.0, 0.75, 0.5, 0.25, 0.1}) {
      for (int a = 0; a < 720 && !found; ++a) {
        const double angle = 2 * M_PI * a / 720;
        Eigen::VectorXd p = q;
        p[0] += radius * opt.step * std::cos(angle) / scale[0];
        p[1] += radius * opt.step * std::sin(angle) / scale[1];
        found = w->space.contains(p) && w->checker.isValid(p);
      }
      if (found) break;
    }
    EXPECT_TRUE(found) << "boundary sample " << i << " at " << q.transpose() << " of obstacle "
                       << s.labels[i] << " has no free configuration within one step";
  }
  EXPECT_GT(checked, 0);
}

TEST(ObstacleSampler, EveryBoundarySampleHasAFreeConfigurationWithinOneStep) {
  expectBoundarySamplesFaceFreeSpace(kThreeObstacles);
  expectBoundarySamplesFaceFreeSpace(
      "robot: {type: point, bounds: {lower: [0, 0], upper: [1, 1]}}\n"
      "obstacles:\n"
      "  - {name: left, shape: box, size: [0.4, 0.6, 1.0], position: [0.3, 0.5, 0]}\n"
      "  - {name: right, shape: box, size: [0.4, 0.6, 1.0], position: [0.5, 0.5, 0]}\n"
      "start: [0.05, 0.1]\ngoal: [0.95, 0.9]\nresolution: 0.01\n");
}

TEST(ObstacleSampler, DeepInteriorSamplesAreNotBoundary) {
  auto w = makeWorld(kThreeObstacles);
  const auto opt = samplerOptions();
  const auto s = planners::sampleObstacles(w->checker, w->space, opt, 22, 1);
  // Interior samples deep inside a box are never marked: the left box spans x in [0.1, 0.3].
  for (int i = 0; i < s.size(); ++i) {
    const Eigen::VectorXd q = s.points.col(i);
    if (s.labels[i] == 1 && q.x() > 0.1 + 2 * opt.step && q.x() < 0.3 - 2 * opt.step &&
        q.y() > 0.2 + 2 * opt.step && q.y() < 0.8 - 2 * opt.step) {
      EXPECT_FALSE(s.boundary[i]) << "deep sample " << q.transpose() << " marked boundary";
    }
  }
}

TEST(ObstacleSampler, ScenarioRootIsTheFirstSampleOfItsTree) {
  auto w = makeWorld(kThreeObstacles);
  const auto s = planners::sampleObstacles(w->checker, w->space, samplerOptions(), 23, 2);
  int first = -1;
  for (int i = 0; i < s.size() && first < 0; ++i)
    if (s.labels[i] == 3) first = i;
  ASSERT_GE(first, 0);
  EXPECT_NEAR((s.points.col(first) - Eigen::Vector2d(0.53, 0.82)).norm(), 0, 1e-15);
}

TEST(ObstacleSampler, RootThatMissesItsObstacleIsReportedNotUsed) {
  std::string yaml = kThreeObstacles;
  yaml.replace(yaml.find("sample: [0.53, 0.82]"), 20, "sample: [0.53, 0.60]");
  auto w = makeWorld(yaml);
  const auto s = planners::sampleObstacles(w->checker, w->space, samplerOptions(), 24, 1);
  ASSERT_EQ(s.tree_sizes.size(), 3u);
  EXPECT_EQ(s.tree_sizes[2], 0);
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_NE(s.warnings[0].find("ball"), std::string::npos) << s.warnings[0];
  for (int label : s.labels) EXPECT_NE(label, 3);
}

// 64 boxes of side 0.04 and one box inside the first, around a point robot: each root is a draw in
// its box's bounds (robots::Robot::configurationAt), which hits the box at once, so the 65 roots
// cost 65 checks. A uniform search costs about 625 draws per box (0.16% of the space each).
TEST(ObstacleSampler, APointRobotsRootsAreDrawnInTheirObstaclesBounds) {
  std::string yaml = "robot: {type: point, bounds: {lower: [0, 0], upper: [1, 1]}}\nobstacles:\n";
  for (int i = 0; i < 8; ++i)
    for (int j = 0; j < 8; ++j)
      yaml += "  - {shape: box, size: [0.04, 0.04, 1], position: [" + std::to_string(0.0625 + 0.125 * i) + ", " +
              std::to_string(0.0625 + 0.125 * j) + ", 0]}\n";
  yaml += "  - {name: inner, shape: box, size: [0.02, 0.02, 1], position: [0.0625, 0.0625, 0]}\n"
          "start: [0.01, 0.01]\ngoal: [0.99, 0.99]\nresolution: 0.01\n";
  auto w = makeWorld(yaml);
  planners::ObstacleSamplerOptions opt;
  opt.samples_per_tree = 1;  // the root only: every check counted is a root's
  const auto [s, checks] = sampleCountingChecks(*w, opt, 27);
  EXPECT_EQ(checks, 65u);
  EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
  ASSERT_EQ(s.tree_sizes.size(), 65u);
  for (int size : s.tree_sizes) EXPECT_EQ(size, 1);
  EXPECT_TRUE(everySampleHitsItsObstacle(*w, s));
}

// Thin rods turned across the axes fill a few percent of their world boxes, but most of their own:
// each root is a draw in the rod's own box, placed (before, 16 draws in the world box missed about
// one rod in nine of 1,500 and each then cost 20,000 uniform draws and a warning).
TEST(ObstacleSampler, AThinTurnedRodsRootIsDrawnInItsOwnBox) {
  std::string yaml = "robot: {type: point, bounds: {lower: [0, 0, 0], upper: [1, 1, 1]}}\nobstacles:\n";
  for (int i = 0; i < 20; ++i)
    yaml += "  - {shape: capsule, radius: 0.004, length: 0.5, position: [" + std::to_string(0.2 + 0.03 * i) +
            ", 0.5, 0.5], rpy: [" + std::to_string(0.3 + 0.1 * i) + ", " + std::to_string(0.7 - 0.05 * i) + ", 0.4]}\n";
  yaml += "start: [0.05, 0.05, 0.05]\ngoal: [0.95, 0.95, 0.95]\nresolution: 0.001\n";
  auto w = makeWorld(yaml);
  planners::ObstacleSamplerOptions opt;
  opt.samples_per_tree = 1;
  const auto [s, checks] = sampleCountingChecks(*w, opt, 27);
  EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
  ASSERT_EQ(s.tree_sizes.size(), 20u);
  EXPECT_LE(checks, 40u);  // a rod and its caps fill about 3/4 of its own box: about 1.3 draws a root
  EXPECT_TRUE(everySampleHitsItsObstacle(*w, s));
}

// A pebble in the path of a 20-link arm stretched out: uniform draws almost never reach it (the arm
// must lie nearly straight), but the blocked straight motion crosses it, and a root is found along
// that motion instead of 20,000 draws and a warning.
TEST(ObstacleSampler, ARootIsFoundAlongAMotionKnownToBeBlocked) {
  std::string lengths, start, goal;
  for (int i = 0; i < 20; ++i) {
    const std::string sep = i ? ", " : "";
    lengths += sep + "0.1", start += sep + "0.06", goal += sep + "-0.06";
  }
  auto w = makeWorld("robot: {type: planar_arm, lengths: [" + lengths + "], widths: 0.02}\n"
                     "obstacles: [{name: pebble, shape: cylinder, radius: 0.05, length: 1, position: [1.95, 0]}]\n"
                     "start: [" + start + "]\ngoal: [" + goal + "]\nresolution: 0.01\n");
  planners::ObstacleSamplerOptions opt;
  opt.samples_per_tree = 20;
  opt.max_root_attempts = 2000;
  const auto [blind, blind_checks] = sampleCountingChecks(*w, opt, 27);
  ASSERT_EQ(blind.warnings.size(), 1u);  // the draws miss it
  EXPECT_NE(blind.warnings[0].find("pebble"), std::string::npos) << blind.warnings[0];
  opt.blocked_motions = {{w->query().start, w->query().goal}};
  const auto [s, checks] = sampleCountingChecks(*w, opt, 27);
  EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
  EXPECT_GT(s.size(), 1);
  EXPECT_TRUE(everySampleHitsItsObstacle(*w, s));
}

// An arm has no configuration at a point, so its roots come from uniform draws: 32 small boxes on a
// ring only the second link reaches. The shared search, naming the box each draw hits, costs less
// than half of what the 32 boxes' own searches cost together (each measured alone in its own world).
TEST(ObstacleSampler, RootsOfManySmallObstaclesComeFromOneSharedSearch) {
  const std::string arm =
      "robot: {type: planar_arm, lengths: [0.6, 0.6], widths: 0.05, limits: {lower: [-pi, -pi], upper: [pi, pi]}}\n"
      "start: [0, 2.5]\ngoal: [1, 2.5]\nresolution: 0.01\nobstacles:\n";  // folded, inside the ring
  std::vector<std::string> boxes;
  for (int k = 0; k < 32; ++k) {
    const double angle = 2 * M_PI * k / 32;
    boxes.push_back("  - {shape: box, size: [0.05, 0.05, 1], position: [" + std::to_string(std::cos(angle)) + ", " +
                    std::to_string(std::sin(angle)) + ", 0]}\n");
  }
  planners::ObstacleSamplerOptions opt;
  opt.samples_per_tree = 1;
  const auto rootChecks = [&](const std::string& yaml, size_t trees) {
    auto w = makeWorld(yaml);
    const auto [s, checks] = sampleCountingChecks(*w, opt, 27);
    EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
    EXPECT_EQ(s.tree_sizes.size(), trees);
    EXPECT_TRUE(everySampleHitsItsObstacle(*w, s));
    return checks;
  };
  std::uint64_t alone = 0;
  std::string all = arm;
  for (const std::string& box : boxes) alone += rootChecks(arm + box, 1), all += box;
  EXPECT_LT(2 * rootChecks(all, 32), alone);
}

// A 2-link arm (reach 1.8 + the links' half width from its base) with a box beyond its reach, one
// just within it and one near the base: the far box costs no root search (before: 200k uniform
// draws, a warning and no samples) and is named in a warning; the box a link's corner can just touch
// is still found and sampled.
TEST(ObstacleSampler, ObstacleBeyondTheArmsReachIsSkippedWithoutSearching) {
  auto w = makeWorld(
      "robot: {type: planar_arm, lengths: [1.0, 0.8], widths: 0.05, limits: {lower: [-pi, -2.5], upper: [pi, 2.5]}}\n"
      "obstacles:\n"
      "  - {name: near, shape: box, size: [0.2, 0.2, 1], position: [0.6, 0.6, 0]}\n"
      "  - {name: rim, shape: box, size: [0.2, 0.2, 1], position: [1.85, 0, 0]}\n"
      "  - {name: far, shape: box, size: [0.2, 0.2, 1], position: [2.0, 0, 0]}\n"
      "start: [0, 0.5]\ngoal: [3, 0.5]\nresolution: 0.01\n");
  planners::ObstacleSamplerOptions opt = smallArmTrees();
  const auto [s, checks] = sampleCountingChecks(*w, opt, 31);
  ASSERT_EQ(s.tree_sizes.size(), 3u);
  EXPECT_GT(s.tree_sizes[0], 0);
  EXPECT_GT(s.tree_sizes[1], 0) << "the rim box is within reach";
  EXPECT_EQ(s.tree_sizes[2], 0);
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_NE(s.warnings[0].find("'far': beyond the robot's reach"), std::string::npos) << s.warnings[0];
  EXPECT_LT(checks, 50000u);
  EXPECT_TRUE(everySampleHitsItsObstacle(*w, s));
}

// Many obstacles out of reach are one warning naming the first ten, not a warning each.
TEST(ObstacleSampler, ObstaclesBeyondReachAreOneWarning) {
  std::string yaml =
      "robot: {type: planar_arm, lengths: [1.0, 0.8], widths: 0.05, limits: {lower: [-pi, -2.5], upper: [pi, 2.5]}}\n"
      "obstacles:\n  - {name: near, shape: box, size: [0.2, 0.2, 1], position: [0.6, 0.6, 0]}\n";
  for (int i = 1; i <= 12; ++i)
    yaml += "  - {name: far" + std::to_string(i) + ", shape: box, size: [0.2, 0.2, 1], position: [" +
            std::to_string(3 + i) + ", 0, 0]}\n";
  auto w = makeWorld(yaml + "start: [0, 0.5]\ngoal: [3, 0.5]\nresolution: 0.01\n");
  planners::ObstacleSamplerOptions opt = smallArmTrees();
  const auto [s, checks] = sampleCountingChecks(*w, opt, 31);
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_EQ(s.warnings[0], "12 obstacles beyond the robot's reach, not sampled: 'far1', 'far2', 'far3', 'far4', "
                           "'far5', 'far6', 'far7', 'far8', 'far9', 'far10' and 2 more");
  EXPECT_EQ(s.unsampled, s.warnings);
}

// Obstacles within reach but beyond the joint limits: no draw hits them. They share one last
// search (each draw that hits anything asked of each) and one warning; each had searched 20,000
// draws of its own (200 such discs: 3.97M checks).
TEST(ObstacleSampler, ObstaclesNoDrawHitsShareOneSearchAndOneWarning) {
  std::string yaml =
      "robot: {type: planar_arm, lengths: [1.0, 0.8], widths: 0.05, limits: {lower: [0, -2.5], upper: [1, 2.5]}}\n"
      "obstacles:\n  - {name: near, shape: box, size: [0.2, 0.2, 1], position: [0.6, 0.6, 0]}\n";
  for (int i = 1; i <= 12; ++i)
    yaml += "  - {name: behind" + std::to_string(i) + ", shape: sphere, radius: 0.05, position: [" +
            std::to_string(1.5 * std::cos(2.3 + 0.1 * i)) + ", " + std::to_string(1.5 * std::sin(2.3 + 0.1 * i)) +
            ", 0]}\n";
  auto w = makeWorld(yaml + "start: [0.1, 0]\ngoal: [0.9, 0]\nresolution: 0.01\n");
  planners::ObstacleSamplerOptions opt = smallArmTrees();
  const auto [s, checks] = sampleCountingChecks(*w, opt, 31);
  EXPECT_GT(s.tree_sizes[0], 0);
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_EQ(s.warnings[0].rfind("12 obstacles hit by no configuration in 20000 uniform samples (beyond the joint "
                                "limits, or small targets: give each `sample:`",
                                0),
            0u)
      << s.warnings[0];
  EXPECT_EQ(s.unsampled, s.warnings);
  EXPECT_LT(checks, 160000u) << "a search each: 12 x 20,000 = 240,000";
  // Cut short by the limit: stopped, and no obstacle reported as missed.
  opt.stop = [] { return true; };
  const auto stopped = sampleCountingChecks(*w, opt, 31).samples;
  EXPECT_TRUE(stopped.stopped);
  for (const std::string& warning : stopped.warnings) EXPECT_EQ(warning.find("no configuration"), std::string::npos);
}

// An obstacle inside a lower-id one: every draw that hits it names the lower id, so the first shared
// search never finds it; the last one asks each draw of it too.
TEST(ObstacleSampler, AnObstacleInsideALowerIdOneFindsItsRoot) {
  auto w = makeWorld(
      "robot: {type: planar_arm, lengths: [1.0, 0.8], widths: 0.05}\n"
      "obstacles:\n"
      "  - {name: outer, shape: box, size: [0.6, 0.6, 1], position: [0.9, 0.6, 0]}\n"
      "  - {name: inner, shape: box, size: [0.2, 0.2, 1], position: [0.9, 0.6, 0]}\n"
      "  - {name: other, shape: box, size: [0.2, 0.2, 1], position: [-1.2, 0, 0]}\n"
      "start: [-0.5, 0]\ngoal: [-2.5, 0]\nresolution: 0.01\n");
  planners::ObstacleSamplerOptions opt = smallArmTrees();
  const auto [s, checks] = sampleCountingChecks(*w, opt, 31);
  ASSERT_EQ(s.tree_sizes.size(), 3u);
  EXPECT_GT(s.tree_sizes[1], 0);
  for (const std::string& warning : s.warnings) EXPECT_EQ(warning.find("'inner'"), std::string::npos) << warning;
  EXPECT_TRUE(everySampleHitsItsObstacle(*w, s));
  // SVMP skips it (Environment::innerObstacles): then only the other two grow trees.
  opt.skip = w->checker.environment().innerObstacles(w->checker.environment().nestedGroups());
  EXPECT_EQ(opt.skip, (std::vector<char>{0, 1, 0}));
  EXPECT_EQ(sampleCountingChecks(*w, opt, 31).samples.tree_sizes.size(), 2u);
}

TEST(ObstacleSampler, SameSeedGivesSameSamplesWithOneAndTwoThreads) {
  auto w = makeWorld(kThreeObstacles);
  const auto opt = samplerOptions();
  const auto one = planners::sampleObstacles(w->checker, w->space, opt, 25, 1);
  const auto two = planners::sampleObstacles(w->checker, w->space, opt, 25, 2);
  ASSERT_EQ(one.size(), two.size());
  EXPECT_TRUE(one.points == two.points);
  EXPECT_EQ(one.labels, two.labels);
  EXPECT_EQ(one.boundary, two.boundary);
  EXPECT_EQ(one.tree_sizes, two.tree_sizes);
  const auto other = planners::sampleObstacles(w->checker, w->space, opt, 26, 1);
  EXPECT_FALSE(other.points == one.points) << "the seed has no effect";
}

// The bounds' samples lie on the faces of the space's box, each face drawn in proportion to its
// measure in the weighted metric: in [0, 4] x [0, 1] with weight 4 on y (scale 2) the faces x = 0, 4
// measure 2 each, y = 0 and y = 1 measure 4 each, so a third of the samples lie on the x faces.
TEST(ObstacleSampler, BoundsSamplesSpreadOverTheFacesByTheirMeasure) {
  auto w = makeWorld(
      "robot: {type: point, bounds: {lower: [0, 0], upper: [4, 1]}}\nobstacles: []\n"
      "start: [0.5, 0.5]\ngoal: [3.5, 0.5]\nresolution: 0.01\nmetric_weights: [1.0, 4.0]\n");
  planners::ObstacleSamples s;
  constexpr int kCount = 3000;
  planners::addBoundsSamples(w->space, kCount, 7, s);
  ASSERT_EQ(s.size(), kCount);
  int on_x_faces = 0;
  for (int i = 0; i < kCount; ++i) {
    const Eigen::Vector2d q = s.points.col(i);
    EXPECT_EQ(s.labels[i], cspace::kJointLimitHit);
    EXPECT_TRUE(s.boundary[i]);
    const bool x_face = q.x() == 0 || q.x() == 4, y_face = q.y() == 0 || q.y() == 1;
    EXPECT_TRUE(x_face || y_face) << q.transpose();
    EXPECT_TRUE(q.x() >= 0 && q.x() <= 4 && q.y() >= 0 && q.y() <= 1) << q.transpose();
    on_x_faces += x_face;
  }
  EXPECT_NEAR(on_x_faces / static_cast<double>(kCount), 1.0 / 3, 0.03);
}

TEST(ObstacleSampler, RejectsInvalidOptions) {
  auto w = makeWorld(kThreeObstacles);
  auto opt = samplerOptions();
  opt.step = 0;
  EXPECT_THROW(planners::sampleObstacles(w->checker, w->space, opt, 1, 1), std::invalid_argument);
  opt = samplerOptions();
  opt.samples_per_tree = 0;
  EXPECT_THROW(planners::sampleObstacles(w->checker, w->space, opt, 1, 1), std::invalid_argument);
}

}  // namespace
}  // namespace svmp::planners
