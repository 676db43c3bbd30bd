// GJK's simplex step: the Voronoi-region fast path against the every-face search it replaced, on
// random segments, triangles and tetrahedra (the origin inside and outside) and on degenerate ones.
#include <gtest/gtest.h>

#include <random>

#include "cspace/gjk_simplex.hpp"

namespace svmp::cspace::gjk {
namespace {

// The kept points as a set of their coordinates' first components (distinct for random points).
std::vector<double> keptKeys(const Simplex& s) {
  std::vector<double> keys;
  for (int i = 0; i < s.n; ++i) keys.push_back(s.p[i].x());
  std::sort(keys.begin(), keys.end());
  return keys;
}

TEST(GjkSimplex, FastPathMatchesTheEveryFaceSearch) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(-1, 1);
  int enclosed = 0, kept_fewer = 0;
  for (int n = 1; n <= 4; ++n)
    for (int trial = 0; trial < 4000; ++trial) {
      Simplex s;
      // Shifted so that the origin is inside some tetrahedra and outside most simplices.
      const Eigen::Vector3d shift = (trial % 3 == 0 ? 0.2 : 1.5) * Eigen::Vector3d(unit(rng), unit(rng), unit(rng));
      for (int i = 0; i < n; ++i) s.p[s.n++] = shift + Eigen::Vector3d(unit(rng), unit(rng), unit(rng));
      Simplex fast = s, reference = s;
      const Eigen::Vector3d x = closestToOrigin(fast), y = closestToOriginByFaces(reference);
      ASSERT_LE((x - y).norm(), 1e-9) << "n " << n << " trial " << trial;
      ASSERT_EQ(keptKeys(fast), keptKeys(reference)) << "n " << n << " trial " << trial;
      enclosed += fast.n == 4;
      kept_fewer += fast.n < n;
    }
  EXPECT_GT(enclosed, 100);     // the origin inside a tetrahedron, often enough to test
  EXPECT_GT(kept_fewer, 8000);  // and the reduction to a face, vertex or edge
}

// Collinear triangles, coplanar tetrahedra and repeated points: the closest point is still the
// hull's (checked against a dense grid of convex combinations), with at most three points kept.
TEST(GjkSimplex, DegenerateSimplicesFallBackToTheEveryFaceSearch) {
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> unit(-1, 1);
  for (int trial = 0; trial < 300; ++trial) {
    const Eigen::Vector3d a(unit(rng), unit(rng), unit(rng)), b(unit(rng), unit(rng), unit(rng)),
        c(unit(rng), unit(rng), unit(rng));
    Simplex s;
    switch (trial % 3) {
      case 0:  // a triangle on a line
        s.p = {a, b, a + 0.3 * (b - a), Eigen::Vector3d::Zero()}, s.n = 3;
        break;
      case 1:  // a tetrahedron in a plane
        s.p = {a, b, c, a + 0.4 * (b - a) + 0.5 * (c - a)}, s.n = 4;
        break;
      default:  // a segment of one point twice
        s.p = {a, a, b, c}, s.n = 2;
        break;
    }
    // The hull is the triangle of the first, second and last-but-at-most-third points.
    const Eigen::Vector3d third = s.p[std::min(s.n, 3) - 1];
    double best = 1e300;
    for (double u = 0; u <= 1; u += 0.01)
      for (double v = 0; u + v <= 1; v += 0.01)
        best = std::min(best, (s.p[0] + u * (s.p[1] - s.p[0]) + v * (third - s.p[0])).norm());
    Simplex fast = s;
    const Eigen::Vector3d x = closestToOrigin(fast);
    EXPECT_TRUE(x.allFinite()) << "trial " << trial;
    EXPECT_LE(x.norm(), best + 1e-12) << "trial " << trial;
    EXPECT_GE(x.norm(), best - 0.03) << "trial " << trial;  // the grid's spacing
    EXPECT_LT(fast.n, 4) << "trial " << trial;
  }
}

}  // namespace
}  // namespace svmp::cspace::gjk
