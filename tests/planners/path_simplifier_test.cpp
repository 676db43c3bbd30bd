// planners/path_simplifier: every segment of a simplified path passes the validator that simplified
// it, start and goal stay, the path never gets longer, the same seed gives the same path, and OMPL's
// smoothness is 0 on a line and matches a hand computation on a right angle; minClearance equals the
// dense scan it skips through, with fewer distance queries.
#include <gtest/gtest.h>

#include <cmath>

#include "cspace/collision_checker.hpp"
#include "planners/path_simplifier.hpp"
#include "test_world.hpp"

namespace svmp::planners {
namespace {

using test::gapScenario;
using test::makeWorld;
using test::readScenario;

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

// Every point a step apart, each measured: what minClearance must equal.
double denseMinClearance(const std::vector<Eigen::VectorXd>& path, const cspace::CollisionChecker& checker,
                         const cspace::ConfigurationSpace& space, double step) {
  double least = checker.clearance(path.front());
  Eigen::VectorXd q(space.dim());
  for (size_t i = 1; i < path.size(); ++i) {
    const double n = std::max(1.0, std::ceil(space.distance(path[i - 1], path[i]) / step));
    for (int k = 1; k <= n; ++k) {
      space.interpolate(path[i - 1], path[i], k / n, q);
      least = std::min(least, checker.clearance(q));
    }
  }
  return least;
}

// Random paths of 2-6 vertices (free or not: through obstacles the minimum is 0 at once, and the
// scan still measures every point near one) among 200 boxes (point robot: FCL's sphere-box distance
// is exact) and on the CRS-F3 of Fig 4.4 (capsules: FCL's GJK, so within its tolerance).
TEST(PathSimplifier, MinClearanceIsTheDenseScansWithFewerQueries) {
  for (const char* name : {"forest_200.yaml", "thesis_fig4_4.yaml"}) {
    auto w = makeWorld(readScenario(name));
    const double step = w->scenario.resolution / 4;
    cspace::Rng rng(7);
    std::uint64_t fast_queries = 0, dense_queries = 0;
    for (int trial = 0; trial < 10; ++trial) {
      std::vector<Eigen::VectorXd> path(2 + trial % 5, Eigen::VectorXd(w->space.dim()));
      for (auto& q : path) w->space.sampleUniform(rng, q);
      std::uint64_t before = w->checker.distanceQueries();
      const double fast = minClearance(path, w->checker, w->space, step);
      fast_queries += w->checker.distanceQueries() - before;
      before = w->checker.distanceQueries();
      const double dense = denseMinClearance(path, w->checker, w->space, step);
      dense_queries += w->checker.distanceQueries() - before;
      EXPECT_NEAR(fast, dense, 1e-9) << name << " trial " << trial;
    }
    EXPECT_LT(fast_queries * 2, dense_queries) << name;
  }
}

}  // namespace
}  // namespace svmp::planners
