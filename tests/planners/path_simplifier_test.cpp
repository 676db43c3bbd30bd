// planners/path_simplifier: every segment of a simplified path passes the validator that simplified
// it, start and goal stay, the path never gets longer, the same seed gives the same path, and OMPL's
// smoothness is 0 on a line and matches a hand computation on a right angle.
#include <gtest/gtest.h>

#include <cmath>

#include "cspace/collision_checker.hpp"
#include "planners/path_simplifier.hpp"
#include "test_world.hpp"

namespace svmp::planners {
namespace {

using test::gapScenario;
using test::makeWorld;

// A zig-zag through the gap: many vertices, much longer than needed.
std::vector<Eigen::VectorXd> zigZag() {
  std::vector<Eigen::VectorXd> path = {Eigen::Vector2d(0.1, 0.1)};
  for (int i = 1; i <= 6; ++i) path.push_back(Eigen::Vector2d(0.05 + 0.05 * i, i % 2 ? 0.45 : 0.15));
  path.push_back(Eigen::Vector2d(0.35, 0.5));
  path.push_back(Eigen::Vector2d(0.65, 0.5));  // through the gap at y = 0.5
  for (int i = 1; i <= 6; ++i) path.push_back(Eigen::Vector2d(0.65 + 0.04 * i, i % 2 ? 0.85 : 0.55));
  path.push_back(Eigen::Vector2d(0.9, 0.9));
  return path;
}

TEST(PathSimplifier, ShortensAndEverySegmentStaysValid) {
  auto w = makeWorld(gapScenario(0.03, "  prm: {}\n"));
  const auto raw = zigZag();
  for (size_t i = 0; i + 1 < raw.size(); ++i) ASSERT_TRUE(w->validator.isValid(raw[i], raw[i + 1])) << i;
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    cspace::Rng rng(seed);
    const SimplifyResult s = simplifyPath(raw, w->validator, w->space, rng);
    ASSERT_GE(s.path.size(), 2u);
    EXPECT_EQ(s.path.front(), raw.front());
    EXPECT_EQ(s.path.back(), raw.back());
    EXPECT_LT(pathLength(s.path, w->space), 0.8 * pathLength(raw, w->space)) << "seed " << seed;
    EXPECT_LT(s.path.size(), raw.size());
    EXPECT_GT(s.segments_proven, 0);
    for (size_t i = 0; i + 1 < s.path.size(); ++i) {
      EXPECT_TRUE(w->checker.isValid(s.path[i]));
      EXPECT_TRUE(w->validator.isValid(s.path[i], s.path[i + 1])) << "seed " << seed << " segment " << i;
    }
    cspace::Rng again(seed);
    EXPECT_EQ(simplifyPath(raw, w->validator, w->space, again).path, s.path);
  }
}

TEST(PathSimplifier, SmoothnessIsOmplsMeasure) {
  auto w = makeWorld(gapScenario(0.03, "  prm: {}\n"));
  const std::vector<Eigen::VectorXd> line = {Eigen::Vector2d(0, 0), Eigen::Vector2d(0.5, 0.5), Eigen::Vector2d(1, 1)};
  EXPECT_NEAR(smoothness(line, w->space), 0.0, 1e-12);
  // Right angle between segments of length 1 and 1: turn pi/2, k = 2 (pi/2) / 2 = pi/2, k^2 = pi^2/4.
  const std::vector<Eigen::VectorXd> corner = {Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 0), Eigen::Vector2d(1, 1)};
  EXPECT_NEAR(smoothness(corner, w->space), M_PI * M_PI / 4, 1e-12);
  EXPECT_NEAR(pathLength(corner, w->space), 2.0, 1e-12);
}

}  // namespace
}  // namespace svmp::planners
