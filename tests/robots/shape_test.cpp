// Shape::contains against the analytic shapes and Shape::validate's messages.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include "robots/shape.hpp"

namespace svmp::robots {
namespace {

constexpr double kEps = 1e-9;

Eigen::Isometry3d translated(double x, double y, double z) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(x, y, z);
  return pose;
}

TEST(ShapeTest, BoxContainsInsideAndFaceButNotBeyond) {
  const Shape box = Shape::box(Eigen::Vector3d(2, 4, 6), translated(1, 0, 0));
  EXPECT_TRUE(box.contains(Eigen::Vector3d(1, 0, 0)));
  EXPECT_TRUE(box.contains(Eigen::Vector3d(2, 2, 3)));  // corner
  EXPECT_TRUE(box.contains(Eigen::Vector3d(2 - kEps, 0, 0)));
  EXPECT_FALSE(box.contains(Eigen::Vector3d(2 + kEps, 0, 0)));
  EXPECT_FALSE(box.contains(Eigen::Vector3d(1, 2 + kEps, 0)));
  EXPECT_FALSE(box.contains(Eigen::Vector3d(1, 0, -3 - kEps)));
}

TEST(ShapeTest, RotatedBoxUsesItsOwnAxes) {
  // A 4 x 0.2 x 0.2 bar turned 90 degrees about z lies along y.
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.rotate(Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitZ()));
  const Shape bar = Shape::box(Eigen::Vector3d(4, 0.2, 0.2), pose);
  EXPECT_TRUE(bar.contains(Eigen::Vector3d(0, 1.9, 0)));
  EXPECT_FALSE(bar.contains(Eigen::Vector3d(1.9, 0, 0)));
}

TEST(ShapeTest, SphereContainsUpToItsRadius) {
  const Shape sphere = Shape::sphere(0.5, translated(0, 0, 1));
  EXPECT_TRUE(sphere.contains(Eigen::Vector3d(0, 0, 1.5 - kEps)));
  EXPECT_FALSE(sphere.contains(Eigen::Vector3d(0, 0, 1.5 + kEps)));
  EXPECT_FALSE(sphere.contains(Eigen::Vector3d(0.4, 0.4, 1)));  // |(0.4,0.4)| = 0.566
}

TEST(ShapeTest, CylinderIsFlatEndedAndCapsuleRounded) {
  // Both have radius 1 and axis length 2 along z; just beyond the flat end on the axis only the capsule
  // (whose caps add a radius) contains the point, and at the rim corner only the cylinder does.
  const Shape cylinder = Shape::cylinder(1, 2);
  const Shape capsule = Shape::capsule(1, 2);
  const Eigen::Vector3d beyond_end(0, 0, 1.5);
  const Eigen::Vector3d rim_corner(1 - kEps, 0, 1 - kEps);
  const Eigen::Vector3d corner_outside_cap(0.9, 0, 1.9);  // |(0.9, 0.9)| > 1 from the cap centre
  EXPECT_FALSE(cylinder.contains(beyond_end));
  EXPECT_TRUE(capsule.contains(beyond_end));
  EXPECT_TRUE(cylinder.contains(rim_corner));
  EXPECT_TRUE(capsule.contains(rim_corner));
  EXPECT_FALSE(capsule.contains(corner_outside_cap));
  EXPECT_TRUE(capsule.contains(Eigen::Vector3d(0, 0, 2 - kEps)));
  EXPECT_FALSE(capsule.contains(Eigen::Vector3d(0, 0, 2 + kEps)));
  EXPECT_FALSE(cylinder.contains(Eigen::Vector3d(1 + kEps, 0, 0)));
}

TEST(ShapeTest, CapsuleBetweenRunsFromAToB) {
  const Eigen::Vector3d a(1, 2, 3), b(1, 2, 1);  // pointing down -z: the antiparallel case
  const Shape capsule = Shape::capsuleBetween(a, b, 0.1);
  EXPECT_EQ(capsule.kind, ShapeKind::kCapsule);
  EXPECT_NEAR(capsule.dims.y(), 2.0, 1e-12);
  EXPECT_TRUE(capsule.contains(a + Eigen::Vector3d(0, 0, 0.1 - kEps)));
  EXPECT_TRUE(capsule.contains(b - Eigen::Vector3d(0, 0, 0.1 - kEps)));
  EXPECT_TRUE(capsule.contains(Eigen::Vector3d(1.1 - kEps, 2, 2)));
  EXPECT_FALSE(capsule.contains(Eigen::Vector3d(1.1 + kEps, 2, 2)));
  EXPECT_FALSE(capsule.contains(b - Eigen::Vector3d(0, 0, 0.1 + kEps)));
}

TEST(ShapeTest, ValidateAcceptsGoodShapes) {
  EXPECT_EQ(Shape::box(Eigen::Vector3d(1, 2, 3)).validate(), "");
  EXPECT_EQ(Shape::sphere(0.1).validate(), "");
  EXPECT_EQ(Shape::cylinder(0.1, 1).validate(), "");
  EXPECT_EQ(Shape::capsule(0.1, 0).validate(), "");  // a zero-length capsule is a sphere
}

TEST(ShapeTest, ValidateNamesTheBadDimension) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(Shape::box(Eigen::Vector3d(1, -2, 3)).validate().find("box sides"), std::string::npos);
  EXPECT_NE(Shape::box(Eigen::Vector3d(1, nan, 3)).validate().find("box sides"), std::string::npos);
  EXPECT_NE(Shape::sphere(0).validate().find("sphere radius"), std::string::npos);
  EXPECT_NE(Shape::cylinder(0.1, 0).validate().find("cylinder length"), std::string::npos);
  EXPECT_NE(Shape::capsule(-1, 1).validate().find("capsule radius"), std::string::npos);
  EXPECT_NE(Shape::capsule(1, -1).validate().find("capsule length"), std::string::npos);
  Shape bad_pose = Shape::sphere(1);
  bad_pose.pose.translation().x() = nan;
  EXPECT_NE(bad_pose.validate().find("pose is not finite"), std::string::npos);
}

// bounds() holds every point contains() accepts, for each kind under a random rotation, and is exact
// for a box along the axes.
TEST(ShapeTest, BoundsHoldTheShape) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> unit(-1, 1);
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translate(Eigen::Vector3d(0.3, -0.2, 0.5));
  pose.rotate(Eigen::AngleAxisd(0.9, Eigen::Vector3d(1, -2, 0.5).normalized()));
  for (const Shape& shape : {Shape::box(Eigen::Vector3d(0.4, 0.1, 0.2), pose), Shape::sphere(0.3, pose),
                             Shape::cylinder(0.1, 0.6, pose), Shape::capsule(0.1, 0.6, pose)}) {
    const Eigen::AlignedBox3d box = shape.bounds();
    const double extent = shape.reach() - pose.translation().norm();  // the ball about its centre
    int inside = 0;
    for (int i = 0; i < 20000; ++i) {
      const Eigen::Vector3d p = pose.translation() + extent * Eigen::Vector3d(unit(rng), unit(rng), unit(rng));
      if (!shape.contains(p)) continue;
      ++inside;
      ASSERT_TRUE(box.contains(p)) << shapeKindName(shape.kind) << " point " << p.transpose();
    }
    EXPECT_GT(inside, 100) << shapeKindName(shape.kind);
  }
  const Eigen::AlignedBox3d exact = Shape::box(Eigen::Vector3d(2, 4, 6), translated(1, 0, 0)).bounds();
  EXPECT_LT((exact.min() - Eigen::Vector3d(0, -2, -3)).norm(), kEps);
  EXPECT_LT((exact.max() - Eigen::Vector3d(2, 2, 3)).norm(), kEps);
}

}  // namespace
}  // namespace svmp::robots
