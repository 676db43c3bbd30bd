// MotionValidator: straight segments checked at the resolution, in the weighted metric.
#include <gtest/gtest.h>

#include <memory>
#include <queue>
#include <random>
#include <vector>

#include "cspace/collision_checker.hpp"
#include "cspace/motion_validator.hpp"
#include "robots/point_robot.hpp"
#include "tests/cspace/recording_checker.hpp"

namespace svmp::cspace {
namespace {

struct WallWorld {
  // A 2-D point robot in [0, 10]^2 and a wall of the given thickness centred at x = wall_x, spanning
  // y in [0, 8] (so the top of the square stays open).
  WallWorld(double wall_x, double thickness)
      : space(Eigen::Vector2d(0, 0), Eigen::Vector2d(10, 10), Eigen::Vector2d(1, 1)),
        checker(std::make_shared<robots::PointRobot>(Eigen::Vector2d(0, 0), Eigen::Vector2d(10, 10)),
                std::make_shared<Environment>(std::vector<Obstacle>{wall(wall_x, thickness)})) {}
  static Obstacle wall(double x, double thickness) {
    Obstacle o;
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translation() = Eigen::Vector3d(x, 4, 0);
    o.shape = robots::Shape::box(Eigen::Vector3d(thickness, 8, 1), pose);
    return o;
  }
  ConfigurationSpace space;
  CollisionChecker checker;
};

TEST(MotionValidatorTest, RejectsASegmentThroughAWallAndAcceptsAFreeOne) {
  WallWorld world(5, 0.1);
  const DiscreteMotionValidator validator(world.checker, world.space, 0.05);
  EXPECT_FALSE(validator.isValid(Eigen::Vector2d(1, 5), Eigen::Vector2d(9, 5)));
  EXPECT_TRUE(validator.isValid(Eigen::Vector2d(1, 9), Eigen::Vector2d(9, 9)));
  EXPECT_TRUE(validator.isValid(Eigen::Vector2d(1, 1), Eigen::Vector2d(1, 9)));
  EXPECT_EQ(validator.calls(), 3u);
  // End points are the caller's: a segment ending inside the wall (x >= 4.95) is valid when its
  // interior is (80 pieces of 0.04975: the last interior point is at x = 4.930).
  EXPECT_TRUE(validator.isValid(Eigen::Vector2d(1, 5), Eigen::Vector2d(4.98, 5)));
  EXPECT_FALSE(validator.isValidIncludingEnd(Eigen::Vector2d(1, 5), Eigen::Vector2d(4.98, 5)));
  EXPECT_TRUE(validator.isValidIncludingEnd(Eigen::Vector2d(1, 9), Eigen::Vector2d(9, 9)));
  EXPECT_THROW(DiscreteMotionValidator(world.checker, world.space, 0), std::invalid_argument);
  EXPECT_THROW(DiscreteMotionValidator(world.checker, world.space, NAN), std::invalid_argument);
}

TEST(MotionValidatorTest, ChecksExactlyTheInteriorPoints) {
  WallWorld world(5, 0.1);
  const DiscreteMotionValidator validator(world.checker, world.space, 0.25);
  // Length 8 at resolution 0.25: 32 pieces, 31 interior points.
  EXPECT_EQ(validator.interiorPoints(8.0), 31);
  EXPECT_EQ(validator.interiorPoints(0.25), 0);
  EXPECT_EQ(validator.interiorPoints(0.26), 1);
  EXPECT_EQ(validator.interiorPoints(0.0), 0);
  std::uint64_t before = world.checker.collisionChecks();
  EXPECT_TRUE(validator.isValid(Eigen::Vector2d(1, 9), Eigen::Vector2d(9, 9)));
  EXPECT_EQ(world.checker.collisionChecks() - before, 31u);
  before = world.checker.collisionChecks();
  EXPECT_TRUE(validator.isValid(Eigen::Vector2d(1, 1), Eigen::Vector2d(1, 1)));
  EXPECT_EQ(world.checker.collisionChecks() - before, 0u);
  // Bisection order: the midpoint goes first, so a wall at the middle costs one check.
  before = world.checker.collisionChecks();
  EXPECT_FALSE(validator.isValid(Eigen::Vector2d(1, 5), Eigen::Vector2d(9, 5)));
  EXPECT_EQ(world.checker.collisionChecks() - before, 1u);
}

TEST(MotionValidatorTest, RefusesASegmentNeedingTooManyChecksInsteadOfCallingItFree) {
  // 2^31 checks once wrapped to a negative count and the segment through the wall passed.
  WallWorld world(5, 0.1);
  const DiscreteMotionValidator validator(world.checker, world.space, 1e-9);
  EXPECT_THROW(validator.isValid(Eigen::Vector2d(1, 5), Eigen::Vector2d(9, 5)), std::length_error);
  double last = -1;
  EXPECT_THROW(validator.checkMotion(Eigen::Vector2d(1, 5), Eigen::Vector2d(9, 5), last), std::length_error);
}

TEST(MotionValidatorTest, CheckMotionReportsTheLastValidFraction) {
  WallWorld world(5, 0.1);
  const DiscreteMotionValidator validator(world.checker, world.space, 0.25);
  double last = -1;
  EXPECT_FALSE(validator.checkMotion(Eigen::Vector2d(1, 5), Eigen::Vector2d(9, 5), last));
  // The wall's face is at x = 4.95: the last sample before it, at 0.25 spacing from x = 1, is 4.75.
  EXPECT_NEAR(1 + 8 * last, 4.75, 1e-12);
  EXPECT_TRUE(validator.checkMotion(Eigen::Vector2d(1, 9), Eigen::Vector2d(9, 9), last));
  const std::uint64_t calls = validator.calls();
  validator.checkMotion(Eigen::Vector2d(1, 9), Eigen::Vector2d(9, 9), last);
  EXPECT_EQ(validator.calls(), calls + 1);
}

TEST(MotionValidatorTest, UsesTheWeightedMetric) {
  WallWorld world(5, 0.1);
  const ConfigurationSpace heavy_x(Eigen::Vector2d(0, 0), Eigen::Vector2d(10, 10), Eigen::Vector2d(4, 1));
  const DiscreteMotionValidator validator(world.checker, heavy_x, 0.25);
  const std::uint64_t before = world.checker.collisionChecks();
  // Metric length of an 8-long x move with w_x = 4 is 16: 64 pieces, 63 interior points.
  EXPECT_TRUE(validator.isValid(Eigen::Vector2d(1, 9), Eigen::Vector2d(9, 9)));
  EXPECT_EQ(world.checker.collisionChecks() - before, 63u);
}

TEST(MotionValidatorTest, WallThinnerThanResolutionCanBeMissedThickerIsAlwaysCaught) {
  // Documented limitation: samples lie every `resolution`; at resolution 0.25 from x = 1 they sit at
  // 1, 1.25, ..., so a 0.01 wall at x in [5.12, 5.13] falls between two samples and is missed.
  {
    WallWorld world(5.125, 0.01);
    const DiscreteMotionValidator validator(world.checker, world.space, 0.25);
    EXPECT_TRUE(validator.isValid(Eigen::Vector2d(1, 5), Eigen::Vector2d(9, 5)));
  }
  // A wall thicker than the sample spacing always contains a sample, wherever it stands.
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> where(2, 8);
  for (int trial = 0; trial < 50; ++trial) {
    WallWorld world(where(rng), 0.26);
    const DiscreteMotionValidator validator(world.checker, world.space, 0.25);
    EXPECT_FALSE(validator.isValid(Eigen::Vector2d(1, 5), Eigen::Vector2d(9, 5)));
  }
}

// The bisection order by a queue of intervals: the midpoints of ever finer intervals, level by level.
std::vector<std::int64_t> queueOrder(std::int64_t segments) {
  std::vector<std::int64_t> order;
  std::queue<std::pair<std::int64_t, std::int64_t>> intervals;
  intervals.emplace(0, segments);
  while (!intervals.empty()) {
    const auto [lo, hi] = intervals.front();
    intervals.pop();
    if (hi - lo < 2) continue;
    const std::int64_t mid = lo + (hi - lo) / 2;
    order.push_back(mid);
    intervals.emplace(lo, mid);
    intervals.emplace(mid, hi);
  }
  return order;
}

// isValid keeps no queue (a queue of n/2 intervals is 16 GB at the 2^30 checks a scenario allows), and
// checks the same points in the same order as one, stopping at the same first collision.
TEST(MotionValidatorTest, BisectionChecksInTheOrderOfAQueueOfIntervals) {
  WallWorld world(5, 0.1);
  const test::RecordingChecker recording(world.checker);
  for (std::int64_t segments = 1; segments <= 70; ++segments) {
    recording.asked.clear();
    // A free row (y = 9) from x = 1 to 9 cut into `segments` pieces.
    const DiscreteMotionValidator validator(recording, world.space, 8.0 / segments + 1e-12);
    EXPECT_TRUE(validator.isValid(Eigen::Vector2d(1, 9), Eigen::Vector2d(9, 9)));
    const std::vector<std::int64_t> expected = queueOrder(segments);
    ASSERT_EQ(recording.asked.size(), expected.size()) << segments;
    for (size_t k = 0; k < expected.size(); ++k)
      EXPECT_NEAR(recording.asked[k][0], 1 + 8.0 * static_cast<double>(expected[k]) / segments, 1e-9)
          << segments << " pieces, check " << k;
  }
  // 8 pieces from x = 0.5 to 8.5 through a wall at x in [3.4, 3.6]: points 4, 2, 6, 1 are free, 3 is not.
  WallWorld wall(3.5, 0.2);
  const test::RecordingChecker walled(wall.checker);
  const DiscreteMotionValidator through(walled, wall.space, 1.0);
  EXPECT_FALSE(through.isValid(Eigen::Vector2d(0.5, 5), Eigen::Vector2d(8.5 - 1e-9, 5)));
  ASSERT_EQ(walled.asked.size(), 5u);
  const double expected[] = {4.5, 2.5, 6.5, 1.5, 3.5};
  for (size_t k = 0; k < 5; ++k) EXPECT_NEAR(walled.asked[k][0], expected[k], 1e-8) << k;
}

// A free segment of 2^20 checks: the calling thread's stop scope ends its check at a poll, reporting
// it blocked; a scope that never fires, or none, lets it run to the end. Scopes nest.
TEST(MotionValidatorTest, AStopScopeEndsALongSegmentsCheckAsBlocked) {
  WallWorld world(5, 0.1);
  const Eigen::Vector2d a(1, 9), b(9, 9);  // a free row
  const DiscreteMotionValidator validator(world.checker, world.space, 8.0 / (1 << 20));
  int polls = 0;
  {
    const MotionStopScope never([] { return false; });
    const MotionStopScope third([&polls] { return ++polls >= 3; });
    const std::uint64_t before = world.checker.collisionChecks();
    EXPECT_FALSE(validator.isValid(a, b));
    EXPECT_EQ(polls, 3);
    EXPECT_EQ(world.checker.collisionChecks() - before, 3 * kStopPollChecks - 1);
    double last_valid = -1;
    EXPECT_FALSE(validator.checkMotion(a, b, last_valid));
    EXPECT_DOUBLE_EQ(last_valid, (kStopPollChecks - 1.0) / (1 << 20));  // the first poll fired
  }
  EXPECT_FALSE(MotionStopScope::stopped());
  const MotionStopScope never([] { return false; });
  EXPECT_TRUE(validator.isValid(a, b));
}

}  // namespace
}  // namespace svmp::cspace
