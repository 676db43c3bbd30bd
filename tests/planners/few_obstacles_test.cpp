// SVMP with few obstacle classes: obstacles one inside another learnt as one, a lone obstacle
// separated from the space's bounds, and nothing to learn at all (the straight motion or the trees
// answer).
#include <gtest/gtest.h>

#include <set>

#include "planners/svmp_planner.hpp"
#include "test_world.hpp"

namespace svmp::planners {
namespace {

using test::makeWorld;
using test::pathIsValid;

// Obstacles one inside another are one class (Environment::nestedGroups): two walls, one of them
// given three times and the other holding a smaller box, train the two classes two walls train.
TEST(FewObstacles, SvmpLearnsNestedObstaclesAsOne) {
  auto w = makeWorld(
      "robot: {type: point, bounds: {lower: [0, 0], upper: [1, 1]}}\n"
      "obstacles:\n"
      "  - {name: left, shape: box, size: [0.1, 0.6, 1.0], position: [0.3, 0.5, 0]}\n"
      "  - {name: left_again, shape: box, size: [0.1, 0.6, 1.0], position: [0.3, 0.5, 0], weight: 3}\n"
      "  - {name: right, shape: box, size: [0.1, 0.6, 1.0], position: [0.7, 0.5, 0]}\n"
      "  - {name: left_once_more, shape: box, size: [0.1, 0.6, 1.0], position: [0.3, 0.5, 0]}\n"
      "  - {name: inside_right, shape: box, size: [0.05, 0.2, 0.5], position: [0.7, 0.45, 0]}\n"
      "start: [0.1, 0.5]\n"
      "goal: [0.9, 0.5]\n"
      "resolution: 0.01\n");
  SvmpPlanner svmp(w->context, SvmpOptions{});
  PhaseTimes times;
  ASSERT_TRUE(svmp.sampleObstacle(1, times));
  const std::set<int> labels(svmp.samples().labels.begin(), svmp.samples().labels.end());
  EXPECT_EQ(labels, (std::set<int>{1, 3}));
  ASSERT_EQ(svmp.trainMultiSvm(times), "");
  EXPECT_EQ(svmp.risk()->numClasses(), 2);
  const PlanResult r = svmp.solve(w->query(), 1);
  ASSERT_TRUE(r.solved()) << r.message;
  EXPECT_TRUE(pathIsValid(*w, r.path));
}

// Only the outermost of nested obstacles are sampled: a post given 50 times samples as the post
// given once (the same trees, seeded by the kept post's id), where it grew 50 trees of one region.
TEST(FewObstacles, SvmpSamplesAShapeGivenManyTimesOnce) {
  const auto world = [](int copies) {
    std::string yaml =
        "robot: {type: point, bounds: {lower: [0, 0], upper: [1, 1]}}\n"
        "obstacles:\n"
        "  - {name: wall, shape: box, size: [0.1, 0.6, 1.0], position: [0.7, 0.5, 0]}\n";
    for (int i = 0; i < copies; ++i) yaml += "  - {shape: cylinder, radius: 0.1, length: 1, position: [0.3, 0.5, 0]}\n";
    return makeWorld(yaml + "start: [0.1, 0.5]\ngoal: [0.9, 0.5]\nresolution: 0.01\n");
  };
  auto once = world(1), many = world(50);
  SvmpPlanner a(once->context, SvmpOptions{}), b(many->context, SvmpOptions{});
  PhaseTimes times;
  ASSERT_TRUE(a.sampleObstacle(3, times));
  ASSERT_TRUE(b.sampleObstacle(3, times));
  EXPECT_EQ(a.samples().labels, b.samples().labels);
  EXPECT_EQ(a.samples().points, b.samples().points);
  EXPECT_EQ(std::set<int>(b.samples().labels.begin(), b.samples().labels.end()), (std::set<int>{1, 2}));
  const PlanResult r = b.solve(many->query(), 3);
  ASSERT_TRUE(r.solved()) << r.message;
  EXPECT_TRUE(pathIsValid(*many, r.path));
}

// One obstacle: the space's bounds are the other class, and the milestones lie between the two,
// where a path rounds the obstacle (one-versus-rest used to refuse the scene as invalid input).
TEST(FewObstacles, SvmpSeparatesALoneObstacleFromTheBounds) {
  auto w = makeWorld(
      "robot: {type: point, bounds: {lower: [0, 0], upper: [1, 1]}}\n"
      "obstacles:\n"
      "  - {name: lonely_box, shape: box, size: [0.2, 0.6, 1.0], position: [0.5, 0.5, 0]}\n"
      "start: [0.1, 0.5]\n"
      "goal: [0.9, 0.5]\n"
      "resolution: 0.01\n");
  SvmpPlanner svmp(w->context, SvmpOptions{});
  PhaseTimes times;
  ASSERT_TRUE(svmp.sampleObstacle(1, times));
  int on_bounds = 0;
  for (int i = 0; i < svmp.samples().size(); ++i) {
    if (svmp.samples().labels[i] != cspace::kJointLimitHit) continue;
    ++on_bounds;
    const Eigen::VectorXd q = svmp.samples().points.col(i);
    EXPECT_NEAR((q.array() * (1 - q.array())).minCoeff(), 0.0, 1e-12) << q.transpose();  // on a face
  }
  EXPECT_EQ(on_bounds, svmp.options().samples_per_tree);
  ASSERT_EQ(svmp.trainMultiSvm(times), "");
  EXPECT_EQ(svmp.risk()->numClasses(), 2);
  ASSERT_TRUE(svmp.findBoundaryMilestones(times));
  // Milestones beside the box on both sides, free.
  bool above = false, below = false;
  for (const auto& q : svmp.roadmap().nodes()) {
    EXPECT_TRUE(w->checker.isValid(q)) << q.transpose();
    above = above || (q.y() > 0.8 && std::abs(q.x() - 0.5) < 0.1);
    below = below || (q.y() < 0.2 && std::abs(q.x() - 0.5) < 0.1);
  }
  EXPECT_TRUE(above && below);
  w->certify();
  for (std::uint64_t seed : {1, 2, 3}) {
    const PlanResult r = w->planner("svmp")->solve(w->query(), seed);
    ASSERT_EQ(r.status, PlanStatus::kSolved) << seed << ": " << r.message;
    EXPECT_TRUE(r.certified);
    EXPECT_TRUE(pathIsValid(*w, r.path));
  }
}

// No obstacle sampled: none at all, or a speck no uniform draw of a 2-link arm's root search hits,
// lying on the straight motion. The roadmap stays empty, the build says why, and the trees answer
// what the straight motion does not (no repair: there is no boundary to repair along).
TEST(FewObstacles, SvmpWithNothingToLearnAnswersByTheStraightMotionOrTrees) {
  const std::string kEmpty =
      "robot: {type: point, bounds: {lower: [0, 0], upper: [1, 1]}}\nobstacles: []\n"
      "start: [0.1, 0.5]\ngoal: [0.9, 0.5]\nresolution: 0.01\n";
  const std::string kSpeck =
      "robot: {type: planar_arm, lengths: [1.0, 1.0], widths: 0.001}\n"
      "obstacles:\n  - {name: speck, shape: box, size: [0.002, 0.002, 1], position: [1.999, 0, 0]}\n"
      "start: [-0.5, 0]\ngoal: [0.5, 0]\nresolution: 0.01\n";
  for (const std::string& yaml : {kEmpty, kSpeck}) {
    auto w = makeWorld(yaml);
    w->certify();
    const bool speck = yaml == kSpeck;
    ASSERT_EQ(w->validator.isValid(w->query().start, w->query().goal), !speck);
    auto svmp = w->planner("svmp");
    for (std::uint64_t seed : {1, 2}) {
      const PlanResult built = svmp->build(seed);
      ASSERT_EQ(built.status, PlanStatus::kSolved) << built.message;
      EXPECT_EQ(built.milestones, 0);
      ASSERT_FALSE(built.warnings.empty());
      EXPECT_NE(built.warnings.back().find("no obstacle was sampled"), std::string::npos) << built.warnings.back();
      const PlanResult r = svmp->query(w->query(), seed);
      ASSERT_EQ(r.status, PlanStatus::kSolved) << yaml << r.message;
      EXPECT_TRUE(r.certified);
      EXPECT_TRUE(pathIsValid(*w, r.path));
      EXPECT_EQ(r.path.size() == 2, !speck) << yaml;
    }
  }
}

}  // namespace
}  // namespace svmp::planners
