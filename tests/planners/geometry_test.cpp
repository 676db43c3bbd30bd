// planners/geometry: the zero level set lies on the analytic curve, hulls contain every point and are
// convex, projected outlines match hand-computed extents.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "planners/geometry.hpp"

namespace svmp::planners {
namespace {

TEST(Geometry, ZeroLevelSetOfACircleLiesOnTheCircleAndClosesIt) {
  const double r = 0.6;
  const auto segments = zeroLevelSet([&](const Point2& p) { return p.squaredNorm() - r * r; },
                                     Point2(-1, -1), Point2(1, 1), 100);
  ASSERT_GT(segments.size(), 100u);
  double length = 0;
  for (const auto& [a, b] : segments) {
    // Linear interpolation of a quadratic along a 0.02 cell edge: off the circle by far less than a cell.
    EXPECT_NEAR(a.norm(), r, 1e-3);
    EXPECT_NEAR(b.norm(), r, 1e-3);
    length += (b - a).norm();
  }
  EXPECT_NEAR(length, 2 * M_PI * r, 0.01);
}

TEST(Geometry, ConvexHullContainsEveryPointAndTurnsLeft) {
  std::mt19937_64 rng(3);
  std::normal_distribution<double> normal;
  for (int trial = 0; trial < 20; ++trial) {
    Polygon points(200);
    for (auto& p : points) p = Point2(normal(rng), normal(rng));
    const Polygon hull = convexHull(points);
    ASSERT_GE(hull.size(), 3u);
    for (size_t i = 0; i < hull.size(); ++i) {
      const Point2 a = hull[i], b = hull[(i + 1) % hull.size()];
      for (const auto& p : points) {  // every point on the left of (or on) every edge
        const double cross = (b - a).x() * (p - a).y() - (b - a).y() * (p - a).x();
        EXPECT_GE(cross, -1e-12);
      }
    }
  }
}

TEST(Geometry, ProjectedOutlineOfARotatedBoxHasItsCorners) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translate(Eigen::Vector3d(1, 2, 0)).rotate(Eigen::AngleAxisd(M_PI / 4, Eigen::Vector3d::UnitZ()));
  const Polygon outline = projectedOutline(robots::Shape::box(Eigen::Vector3d(2, 2, 1)), pose, 16);
  ASSERT_EQ(outline.size(), 4u);  // the top and bottom faces project on each other
  for (const auto& p : outline) EXPECT_NEAR((p - Point2(1, 2)).norm(), std::sqrt(2.0), 1e-12);
  const Polygon circle = projectedOutline(robots::Shape::sphere(0.5), Eigen::Isometry3d::Identity(), 32);
  EXPECT_EQ(circle.size(), 32u);
  for (const auto& p : circle) EXPECT_NEAR(p.norm(), 0.5, 1e-12);
}

}  // namespace
}  // namespace svmp::planners
