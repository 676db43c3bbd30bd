// distanceLowerBound for every pair of primitives: never above the distance of any two points of
// the shapes, exact where the distance is known in closed form, not positive when they overlap, and
// close to FCL's value where FCL is right.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include <fcl/narrowphase/collision.h>

#include "cspace/convex_distance.hpp"
#include "tests/cspace/fcl_geometry.hpp"

namespace svmp::cspace {
namespace {

using robots::Shape;
using test::fclGeometry;

Shape randomShape(int kind, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> size(0.05, 0.4);
  switch (kind) {
    case 0:
      return Shape::box(Eigen::Vector3d(size(rng), size(rng), size(rng)));
    case 1:
      return Shape::sphere(size(rng));
    case 2:
      return Shape::capsule(0.5 * size(rng), size(rng));
    default:
      return Shape::cylinder(size(rng), size(rng));
  }
}

Eigen::Isometry3d randomPose(std::mt19937_64& rng, double spread) {
  std::uniform_real_distribution<double> unit(-1, 1);
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() =
      Eigen::Quaterniond(Eigen::Vector4d(unit(rng), unit(rng), unit(rng), unit(rng)).normalized())
          .toRotationMatrix();
  pose.translation() = spread * Eigen::Vector3d(unit(rng), unit(rng), unit(rng));
  return pose;
}

// Points of the shape (frame coordinates, shape pose identity), by rejection from its bounding
// cube.
std::vector<Eigen::Vector3d> pointsIn(const Shape& s, int n, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(-1, 1);
  const double r = s.reach();
  std::vector<Eigen::Vector3d> points;
  while (static_cast<int>(points.size()) < n) {
    const Eigen::Vector3d p = r * Eigen::Vector3d(unit(rng), unit(rng), unit(rng));
    if (s.contains(p)) points.push_back(p);
  }
  return points;
}

TEST(ConvexDistanceTest, NeverAboveThePointsDistanceAndNotPositiveWhenOverlapping) {
  std::mt19937_64 rng(4);
  for (int ka = 0; ka < 4; ++ka)
    for (int kb = ka; kb < 4; ++kb)
      for (int trial = 0; trial < 30; ++trial) {
        const Shape a = randomShape(ka, rng), b = randomShape(kb, rng);
        const Eigen::Isometry3d pa = randomPose(rng, 0.5), pb = randomPose(rng, 0.5);
        const double lower = distanceLowerBound(a, pa, b, pb, pa.translation() - pb.translation());
        double upper = 1e300;
        bool overlap = false;
        const auto points_a = pointsIn(a, 200, rng), points_b = pointsIn(b, 200, rng);
        for (const auto& x : points_a) {
          overlap = overlap || b.contains(pb.inverse() * (pa * x));
          for (const auto& y : points_b) upper = std::min(upper, (pa * x - pb * y).norm());
        }
        EXPECT_LE(lower, upper + 1e-12) << "kinds " << ka << ", " << kb << " trial " << trial;
        if (overlap) {
          EXPECT_LE(lower, 0.0) << "kinds " << ka << ", " << kb << " trial " << trial;
        }
      }
}

// Capsules against boxes, as the certified validator asks for a link near an obstacle: within the
// validator's 1e-3 of the distance however close they come (GJK runs on the capsule's segment, so
// it ends exactly). The distance: the segment's nearest point to the box, by golden-section search
// (the point-box distance is convex along the segment).
TEST(ConvexDistanceTest, CapsuleAgainstBoxWithinTheRequestedGapDownToContact) {
  std::mt19937_64 rng(11);
  const Shape box = Shape::box(Eigen::Vector3d(0.6, 0.4, 0.02));
  const Eigen::Vector3d half(0.3, 0.2, 0.01);
  auto pointToBox = [&](const Eigen::Vector3d& p) { return (p.cwiseAbs() - half).cwiseMax(0.0).norm(); };
  for (int trial = 0; trial < 200; ++trial) {
    const Shape capsule = Shape::capsule(0.04, 0.3);
    Eigen::Isometry3d pose = randomPose(rng, 0);
    const Eigen::Vector3d axis = pose.linear().col(2);
    auto segmentDistance = [&](const Eigen::Isometry3d& at) {
      double lo = -0.15, hi = 0.15;
      const double g = 0.5 * (std::sqrt(5.0) - 1);
      auto at_t = [&](double t) { return pointToBox(at.translation() + t * axis); };
      for (int i = 0; i < 200; ++i) {
        const double m1 = hi - g * (hi - lo), m2 = lo + g * (hi - lo);
        if (at_t(m1) < at_t(m2))
          hi = m2;
        else
          lo = m1;
      }
      return at_t(0.5 * (lo + hi)) - 0.04;
    };
    // Above the board, then lowered until the gap is 10^-(1..5) m.
    pose.translation() = Eigen::Vector3d(0.1, -0.05, 0.5);
    const double start = segmentDistance(pose);
    for (double gap : {1e-1, 1e-2, 1e-3, 1e-4, 1e-5}) {
      Eigen::Isometry3d at = pose;
      at.translation().z() -= start - gap;
      const double truth = segmentDistance(at);
      const double lower = distanceLowerBound(capsule, at, box, Eigen::Isometry3d::Identity(),
                                              at.translation(), 1e-3);
      EXPECT_LE(lower, truth + 1e-12) << "trial " << trial << " gap " << gap;
      EXPECT_GE(lower, (1 - 1e-3) * truth - 1e-12) << "trial " << trial << " gap " << gap;
    }
  }
}

// A caller keeping the least distance over pairs passes its least as `enough`: the run may stop
// once beyond it, so the least is the same as with the full run, and the run stops early for some
// pairs (else the parameter did nothing).
TEST(ConvexDistanceTest, StoppingBeyondEnoughKeepsTheLeastOverPairs) {
  std::mt19937_64 rng(21);
  std::uniform_real_distribution<double> fraction(0.2, 1.5);
  int earlier = 0;
  for (int ka = 0; ka < 4; ++ka)
    for (int kb = 0; kb < 4; ++kb)
      for (int trial = 0; trial < 50; ++trial) {
        const Shape a = randomShape(ka, rng), b = randomShape(kb, rng);
        const Eigen::Isometry3d pa = randomPose(rng, 0.8), pb = randomPose(rng, 0.8);
        const Eigen::Vector3d hint = pa.translation() - pb.translation();
        const double full = distanceLowerBound(a, pa, b, pb, hint, 1e-6);
        const double least = fraction(rng) * std::max(full, 1e-3);  // the other pairs' least
        const double cut = distanceLowerBound(a, pa, b, pb, hint, 1e-6, least);
        EXPECT_LE(cut, full) << "kinds " << ka << ", " << kb << " trial " << trial;
        EXPECT_EQ(std::min(cut, least), std::min(full, least)) << "kinds " << ka << ", " << kb << " trial " << trial;
        earlier += cut < full;
      }
  EXPECT_GT(earlier, 20);
}

// The checker's narrow phase against FCL's on every pair of primitives, half of them placed near
// contact (the second shape slid along the centres' line to within 1 mm of the first's bound):
// wherever our GJK decides, it decides as FCL does, and it leaves few pairs to FCL.
TEST(ConvexDistanceTest, IntersectsAgreesWithFclAndRarelyDefers) {
  std::mt19937_64 rng(21);
  std::uniform_real_distribution<double> gap(-1e-3, 1e-3);
  int decided = 0, total = 0, hits = 0, near_pairs = 0;
  for (int ka = 0; ka < 4; ++ka)
    for (int kb = 0; kb < 4; ++kb)
      for (int trial = 0; trial < 400; ++trial) {
        const Shape a = randomShape(ka, rng), b = randomShape(kb, rng);
        const Eigen::Isometry3d pa = randomPose(rng, 0.4);
        Eigen::Isometry3d pb = randomPose(rng, 0.4);
        if (trial % 2) {  // near contact: slide b until the separating bound is about `gap`
          const Eigen::Vector3d axis = (pb.translation() - pa.translation()).normalized();
          for (int step = 0; step < 60; ++step) {
            const double d = distanceLowerBound(a, pa, b, pb, pa.translation() - pb.translation(), 1e-9);
            const double move = d > 0 ? d - gap(rng) : 0.05;
            pb.translation() += (d > 0 ? -move : move) * axis;
            if (d > 0 && std::abs(move) < 1e-3) break;
          }
        }
        if (trial % 2)
          near_pairs += distanceLowerBound(a, pa, b, pb, pa.translation() - pb.translation(), 1e-9) < 1.1e-3;
        fcl::CollisionObjectd oa(fclGeometry(a), pa.linear(), pa.translation());
        fcl::CollisionObjectd ob(fclGeometry(b), pb.linear(), pb.translation());
        fcl::CollisionRequestd request;
        fcl::CollisionResultd result;
        const bool fcl_hit = fcl::collide(&oa, &ob, request, result) > 0;
        const auto ours = intersects(a, pa, b, pb);
        ++total;
        hits += fcl_hit;
        if (!ours) continue;
        ++decided;
        EXPECT_EQ(*ours, fcl_hit) << "kinds " << ka << ", " << kb << " trial " << trial;
      }
  EXPECT_GT(hits, total / 5);          // both answers well represented
  EXPECT_LT(hits, 4 * total / 5);
  EXPECT_GT(decided, 0.95 * total);  // FCL's fallback stays rare
  EXPECT_GT(near_pairs, 0.9 * total / 2);  // the slide found contact's neighbourhood
}

TEST(ConvexDistanceTest, ExactForSpheresAndForAPointAgainstABox) {
  const Shape s1 = Shape::sphere(0.3), s2 = Shape::sphere(0.2),
              cube = Shape::box(Eigen::Vector3d(1, 2, 3));
  Eigen::Isometry3d p1 = Eigen::Isometry3d::Identity(), p2 = Eigen::Isometry3d::Identity();
  p2.translation() = Eigen::Vector3d(1, 2, 2);  // centres 3 apart
  const double spheres =
      distanceLowerBound(s1, p1, s2, p2, Eigen::Vector3d::UnitX());  // a poor hint
  EXPECT_GT(spheres, (1 - 1e-6) * 2.5);
  EXPECT_LE(spheres, 2.5 + 1e-12);
  // A small sphere off the box's corner (0.5, 1, 1.5) by (1, 1, 1): distance sqrt(3) - 0.2.
  Eigen::Isometry3d corner = Eigen::Isometry3d::Identity();
  corner.translation() = Eigen::Vector3d(1.5, 2, 2.5);
  const double d = distanceLowerBound(cube, Eigen::Isometry3d::Identity(), s2, corner,
                                      -Eigen::Vector3d::UnitZ());
  EXPECT_GT(d, (1 - 1e-6) * (std::sqrt(3.0) - 0.2));
  EXPECT_LE(d, std::sqrt(3.0) - 0.2 + 1e-12);
  // Separation along a given direction: two unit cubes 3 apart along x, seen along x and along y.
  const Shape unit = Shape::box(Eigen::Vector3d::Ones());
  Eigen::Isometry3d right = Eigen::Isometry3d::Identity();
  right.translation() = Eigen::Vector3d(3, 0, 0);
  EXPECT_NEAR(
      separationAlong(unit, Eigen::Isometry3d::Identity(), unit, right, Eigen::Vector3d(-1, 0, 0)),
      2, 1e-12);
  EXPECT_LT(
      separationAlong(unit, Eigen::Isometry3d::Identity(), unit, right, Eigen::Vector3d(0, 1, 0)),
      0);
}

// A tilted cube of side 1e4 whose corner comes within 1e-8 of a small box's face (a probe's tool
// box beside a wall): the two are apart, and the certifier's distance bound sees the gap, so a
// configuration it proves is one check() calls free. The overlap test once widened every face by
// 1e-12 of the other box's size (1.5e-8 here) and called them touching; 1e-8 into the face they touch.
TEST(ConvexDistanceTest, AHugeBoxsCornerJustOffASmallBoxsFaceIsApart) {
  const Shape tool = Shape::box(Eigen::Vector3d(0.02, 0.02, 0.02)), wall = Shape::box(Eigen::Vector3d::Constant(1e4));
  Eigen::Isometry3d wall_pose = Eigen::Isometry3d::Identity();
  wall_pose.linear() = (Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()) *
                        Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitY())).toRotationMatrix();
  // The wall's corner nearest the tool: the one farthest along -x in the world.
  Eigen::Vector3d corner_local;
  for (int k = 0; k < 3; ++k) corner_local[k] = wall_pose.linear()(0, k) > 0 ? -5e3 : 5e3;
  for (const double gap : {1e-8, -1e-8}) {
    // The tool's face at x = 0.01; the corner at x = 0.01 + gap, y = z = 0 (over the face's centre).
    wall_pose.translation() = Eigen::Vector3d(0.01 + gap, 0, 0) - wall_pose.linear() * corner_local;
    const Eigen::Vector3d corner = wall_pose * corner_local;
    ASSERT_NEAR(corner.x(), 0.01 + gap, 1e-11);
    const auto hit = intersects(tool, Eigen::Isometry3d::Identity(), wall, wall_pose);
    ASSERT_TRUE(hit.has_value());
    EXPECT_EQ(*hit, gap < 0) << "gap " << gap;
    const double d = distanceLowerBound(tool, Eigen::Isometry3d::Identity(), wall, wall_pose, Eigen::Vector3d::UnitX(), 1e-9);
    if (gap > 0) EXPECT_GT(d, 0.5 * gap);
    else EXPECT_LE(d, 0.0);
  }
}

// A sphere against a cylinder in closed form, on a turned pole 10,000 long and 0.05 in radius, where GJK
// had stalled and FCL reported a point 3e-5 from its side as touching: beside its side, off its rim
// and over its cap, in either order; inside it, touching.
TEST(ConvexDistanceTest, ExactForASphereAgainstALongCylinder) {
  const Shape pole = Shape::cylinder(0.05, 10000), ball = Shape::sphere(1e-6);
  Eigen::Isometry3d pole_pose = Eigen::Isometry3d::Identity();
  pole_pose.linear() = (Eigen::AngleAxisd(-1.4787, Eigen::Vector3d::UnitX()) *
                        Eigen::AngleAxisd(0.0822, Eigen::Vector3d::UnitY()) *
                        Eigen::AngleAxisd(0.0813, Eigen::Vector3d::UnitZ())).toRotationMatrix();
  pole_pose.translation() = Eigen::Vector3d(0.3, -0.2, 0.1);
  struct Case {
    Eigen::Vector3d local;  // the ball's centre in the pole's frame
    double distance;
  };
  const double r = 1e-6;
  for (const Case& c : {Case{{0.05 + 3e-5 + r, 0, 1234.5}, 3e-5},
                        Case{{0, -(0.05 + 0.01), -4321}, 0.01 - r},
                        Case{{0.05 + 0.3, 0, 5000 + 0.4}, 0.5 - r},
                        Case{{0.01, 0.02, -5000 - 0.2}, 0.2 - r}}) {
    Eigen::Isometry3d at = Eigen::Isometry3d::Identity();
    at.translation() = pole_pose * c.local;
    for (bool swap : {false, true}) {
      const double d = swap ? distanceLowerBound(ball, at, pole, pole_pose, Eigen::Vector3d::UnitX())
                            : distanceLowerBound(pole, pole_pose, ball, at, Eigen::Vector3d::UnitX());
      EXPECT_NEAR(d, c.distance, 1e-9) << c.local.transpose();
      EXPECT_EQ(swap ? intersects(ball, at, pole, pole_pose) : intersects(pole, pole_pose, ball, at),
                std::optional<bool>(false));
    }
  }
  Eigen::Isometry3d inside = Eigen::Isometry3d::Identity();
  inside.translation() = pole_pose * Eigen::Vector3d(0.05 - 1e-5, 0, 4999);
  EXPECT_EQ(intersects(ball, inside, pole, pole_pose), std::optional<bool>(true));
  EXPECT_LE(distanceLowerBound(ball, inside, pole, pole_pose, Eigen::Vector3d::UnitX()), 0.0);
}

}  // namespace
}  // namespace svmp::cspace
