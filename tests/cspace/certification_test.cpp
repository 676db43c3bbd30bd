// Certified motion validation: a corner cut between two samples is rejected where the sampled check
// accepts it; on random segments for every robot type a certified segment is always free under a dense
// brute-force check (soundness) and clearly free segments are certified (completeness); the distance
// and displacement bounds it rests on are checked against hand computations and sampled motion.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <random>

#include "cspace/certified_motion_validator.hpp"
#include "cspace/collision_checker.hpp"
#include "robots/dh_arm.hpp"
#include "robots/planar_arm.hpp"
#include "robots/point_robot.hpp"

namespace svmp::cspace {
namespace {

using robots::Shape;
constexpr double kPi = std::numbers::pi;

Obstacle box(const Eigen::Vector3d& size, const Eigen::Vector3d& centre) {
  Obstacle o;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = centre;
  o.shape = Shape::box(size, pose);
  return o;
}

Obstacle sphere(double r, const Eigen::Vector3d& centre) {
  Obstacle o;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = centre;
  o.shape = Shape::sphere(r, pose);
  return o;
}

// Minimum of a convex function on [lo, hi] (ternary search).
template <class F>
double convexMin(F f, double lo, double hi) {
  for (int k = 0; k < 100; ++k) {
    const double m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3;
    if (f(m1) < f(m2))
      hi = m2;
    else
      lo = m1;
  }
  return f(0.5 * (lo + hi));
}

// Distance from world point p to a box placed at `pose` (0 inside).
double pointBoxDistance(const Eigen::Vector3d& p, const Shape& box, const Eigen::Isometry3d& pose) {
  return ((pose.inverse() * p).cwiseAbs() - 0.5 * box.dims).cwiseMax(0.0).norm();
}

TEST(Certification, CornerCutBetweenSamplesIsRejectedWhereSamplingAcceptsIt) {
  // A unit box at the origin; the segment c -> d on the line x + y = -0.9 crosses its corner near
  // (-0.45, -0.45). At resolution 1 its two samples, (-0.8, -0.1) and (-0.1, -0.8), miss the box.
  const auto robot = std::make_shared<robots::PointRobot>(Eigen::Vector2d(-5, -5), Eigen::Vector2d(5, 5));
  const auto env = std::make_shared<Environment>(std::vector<Obstacle>{box({1, 1, 1}, {0, 0, 0})});
  const CollisionChecker checker(robot, env);
  const ConfigurationSpace space(Eigen::Vector2d(-5, -5), Eigen::Vector2d(5, 5), Eigen::Vector2d(1, 1));
  const Eigen::Vector2d c(-1.5, 0.6), d(0.6, -1.5);
  ASSERT_FALSE(checker.isValid(0.5 * (c + d)));
  const DiscreteMotionValidator sampled(checker, space, 1.0);
  const CertifiedMotionValidator certified(checker, space, 1.0);
  EXPECT_TRUE(sampled.isValid(c, d));
  EXPECT_FALSE(certified.isValid(c, d));
  // 1.5 above the box's top face all along: proven.
  EXPECT_TRUE(certified.isValid(Eigen::Vector2d(-2, 1), Eigen::Vector2d(1, 2)));
  // Straight into the face x = -0.5: proven up to it (robot radius 1e-6), never beyond.
  double last = -1;
  EXPECT_FALSE(certified.checkMotion(Eigen::Vector2d(-2, 0), Eigen::Vector2d(2, 0), last));
  EXPECT_LE(-2 + 4 * last, -0.5);
  EXPECT_GT(-2 + 4 * last, -0.51);
  EXPECT_EQ(certified.calls(), 3u);
  EXPECT_GT(certified.distanceQueries(), 3u);
}

TEST(Certification, FreeDistanceMatchesHandComputation) {
  const auto robot = std::make_shared<robots::PointRobot>(Eigen::Vector3d::Constant(-5), Eigen::Vector3d::Constant(5));
  const auto env = std::make_shared<Environment>(
      std::vector<Obstacle>{sphere(1, {0, 0, 0}), box({4, 4, 4}, {3.5, 3.5, 3.5})});
  const CollisionChecker checker(robot, env);
  // Robot radius 1e-6.
  EXPECT_NEAR(checker.freeDistance(Eigen::Vector3d(-2, 0, 0)), 1 - 1e-6, 1e-9);
  EXPECT_NEAR(checker.freeDistance(Eigen::Vector3d(0, -3, 0)), 2 - 1e-6, 1e-9);
  EXPECT_EQ(checker.freeDistance(Eigen::Vector3d(0.2, 0.1, 0)), 0.0);    // inside the sphere
  EXPECT_EQ(checker.freeDistance(Eigen::Vector3d(3.5, 3.5, 3.5)), 0.0);  // deep inside the box
  EXPECT_EQ(checker.freeDistance(Eigen::Vector3d(6, 0, 0)), 0.0);        // outside the limits
}

struct RobotCase {
  std::string name;
  std::shared_ptr<const robots::Robot> robot;
  double resolution;
};

std::vector<RobotCase> robotCases() {
  std::vector<RobotCase> cases;
  cases.push_back({"point2d", std::make_shared<robots::PointRobot>(Eigen::Vector2d(-2, -2), Eigen::Vector2d(2, 2)), 0.01});
  cases.push_back({"point3d", std::make_shared<robots::PointRobot>(Eigen::Vector3d::Constant(-2), Eigen::Vector3d::Constant(2)), 0.01});
  cases.push_back({"planar3", std::make_shared<robots::PlanarArm>(std::vector<double>{0.8, 0.6, 0.4}, std::vector<double>(3, 0.08),
                                                                   Eigen::VectorXd::Constant(3, -kPi), Eigen::VectorXd::Constant(3, kPi)), 0.01});
  cases.push_back({"crs_f3", std::make_shared<robots::DhArm>(robots::crsF3Spec(6)), 0.02});
  return cases;
}

TEST(Certification, CertifiedSegmentsAreFreeUnderADenseCheckAndClearOnesAreCertified) {
  std::mt19937_64 rng(17);
  for (const auto& c : robotCases()) {
    SCOPED_TRACE(c.name);
    std::uniform_real_distribution<double> unit(-1, 1);
    std::vector<Obstacle> obstacles;
    const double scale = c.robot->workspaceDim() == 2 ? 1.5 : 0.8;
    for (int i = 0; i < 6; ++i) {
      const Eigen::Vector3d centre(scale * unit(rng), scale * unit(rng), c.robot->workspaceDim() == 2 ? 0 : 0.5 + 0.5 * unit(rng));
      obstacles.push_back(i % 2 ? sphere(0.1 + 0.05 * unit(rng), centre) : box(Eigen::Vector3d::Constant(0.2 + 0.05 * unit(rng)), centre));
    }
    const auto env = std::make_shared<Environment>(std::move(obstacles));
    const CollisionChecker checker(c.robot, env);
    const Eigen::VectorXd& lo = c.robot->lowerLimits();
    const Eigen::VectorXd& hi = c.robot->upperLimits();
    const ConfigurationSpace space(lo, hi, Eigen::VectorXd::Ones(lo.size()));
    const CertifiedMotionValidator certified(checker, space, c.resolution);
    const DiscreteMotionValidator dense(checker, space, c.resolution / 50);
    int proven = 0, clear = 0, clear_proven = 0;
    for (int trial = 0; trial < 150; ++trial) {
      Eigen::VectorXd a(lo.size()), b(lo.size());
      for (int d = 0; d < a.size(); ++d) {
        a[d] = lo[d] + (hi[d] - lo[d]) * 0.5 * (1 + unit(rng));
        b[d] = std::clamp(a[d] + 0.3 * (hi[d] - lo[d]) * unit(rng) / std::sqrt(double(a.size())), lo[d], hi[d]);
      }
      if (!checker.isValid(a) || !checker.isValid(b)) continue;
      const bool ok = certified.isValid(a, b);
      const bool dense_ok = dense.isValid(a, b);
      if (ok) {
        ++proven;
        EXPECT_TRUE(dense_ok) << "certified but collides: [" << a.transpose() << "] -> [" << b.transpose() << "]";
      }
      // Clear: the smallest free distance over a dense walk is far above the tolerance.
      double min_d = 1e300;
      for (int k = 0; k <= 200; ++k) min_d = std::min(min_d, checker.freeDistance(a + (k / 200.0) * (b - a)));
      if (min_d > 1e-2) {
        ++clear;
        clear_proven += ok;
      }
    }
    EXPECT_GT(proven, 10);
    EXPECT_GT(clear, 10);
    EXPECT_EQ(clear_proven, clear) << "clear segments not certified";
    std::printf("[ info     ] %s: %d certified, %d of %d clear segments certified, %.1f distance queries per call\n",
                c.name.c_str(), proven, clear_proven, clear,
                static_cast<double>(certified.distanceQueries()) / certified.calls());
  }
}

// Random segments either collide or pass far away; a certifier too permissive (a wrong displacement
// bound, a missing self-collision pair) shows only on segments that graze an obstacle. Each segment
// here starts within a resolution of contact (bisected towards a colliding configuration) and ends a
// few resolutions away from it; every one certified must pass the dense check. The Panda, with its
// base column and self-collision pairs, included.
TEST(Certification, GrazingSegmentsCertifiedAreFreeUnderADenseCheck) {
  std::mt19937_64 rng(23);
  auto cases = robotCases();
  cases.push_back({"panda", std::make_shared<robots::DhArm>(robots::pandaSpec()), 0.02});
  for (const auto& c : cases) {
    SCOPED_TRACE(c.name);
    std::uniform_real_distribution<double> unit(-1, 1);
    std::vector<Obstacle> obstacles;
    const double scale = c.robot->workspaceDim() == 2 ? 1.2 : 0.6;
    const bool arm3d = dynamic_cast<const robots::DhArm*>(c.robot.get()) != nullptr;
    for (int i = 0; i < 6; ++i) {
      Eigen::Vector3d centre(scale * unit(rng), scale * unit(rng), c.robot->workspaceDim() == 2 ? 0 : 0.5 + 0.4 * unit(rng));
      if (arm3d) centre.head<2>() *= (0.45 + 0.15 * unit(rng)) / centre.head<2>().norm();  // clear of the base
      obstacles.push_back(i % 2 ? sphere(0.12 + 0.05 * unit(rng), centre) : box(Eigen::Vector3d::Constant(0.25 + 0.05 * unit(rng)), centre));
    }
    const CollisionChecker checker(c.robot, std::make_shared<Environment>(std::move(obstacles)));
    const Eigen::VectorXd& lo = c.robot->lowerLimits();
    const Eigen::VectorXd& hi = c.robot->upperLimits();
    const ConfigurationSpace space(lo, hi, Eigen::VectorXd::Ones(lo.size()));
    const CertifiedMotionValidator certified(checker, space, c.resolution);
    const DiscreteMotionValidator dense(checker, space, c.resolution / 50);
    auto draw = [&] {
      Eigen::VectorXd q(lo.size());
      for (int d = 0; d < q.size(); ++d) q[d] = lo[d] + (hi[d] - lo[d]) * 0.5 * (1 + unit(rng));
      return q;
    };
    int grazing = 0, proven = 0;
    for (int trial = 0; trial < 400 && grazing < 150; ++trial) {
      Eigen::VectorXd free = draw(), hit = draw();
      for (int k = 0; k < 1000 && checker.isValid(hit); ++k) hit = draw();
      if (!checker.isValid(free) || checker.isValid(hit)) continue;
      // Bisect until free lies within a resolution of contact, but not within the certifier's tolerance.
      for (int k = 0; k < 60 && checker.freeDistance(free) > c.resolution; ++k) {
        const Eigen::VectorXd mid = 0.5 * (free + hit);
        (checker.isValid(mid) ? free : hit) = mid;
      }
      if (checker.freeDistance(free) > c.resolution) continue;
      Eigen::VectorXd offset(lo.size());
      for (int d = 0; d < offset.size(); ++d) offset[d] = unit(rng);
      const Eigen::VectorXd end = (free + 5 * c.resolution * offset.normalized()).cwiseMax(lo).cwiseMin(hi);
      if (!checker.isValid(end)) continue;
      ++grazing;
      if (!certified.isValid(free, end)) continue;
      ++proven;
      EXPECT_TRUE(dense.isValid(free, end)) << "certified but collides: [" << free.transpose() << "] -> [" << end.transpose() << "]";
    }
    std::printf("[ info     ] %s: %d of %d grazing segments certified\n", c.name.c_str(), proven, grazing);
    EXPECT_GT(grazing, 50);
    EXPECT_GT(proven, 10) << "soundness never exercised near contact";
  }
}

TEST(Certification, DisplacementBoundIsNeverExceededBySampledMotion) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> unit(0, 1);
  auto cases = robotCases();
  cases.push_back({"panda", std::make_shared<robots::DhArm>(robots::pandaSpec()), 0.02});
  for (const auto& c : cases) {
    SCOPED_TRACE(c.name);
    const auto& robot = *c.robot;
    robots::Poses start, moved;
    double worst = 0;
    for (int trial = 0; trial < 200; ++trial) {
      Eigen::VectorXd a(robot.dof()), b(robot.dof());
      for (int d = 0; d < a.size(); ++d) {
        a[d] = robot.lowerLimits()[d] + unit(rng) * (robot.upperLimits()[d] - robot.lowerLimits()[d]);
        b[d] = robot.lowerLimits()[d] + unit(rng) * (robot.upperLimits()[d] - robot.lowerLimits()[d]);
      }
      const double bound = robot.displacementBound(a, b);
      Eigen::VectorXd link_bound;
      robot.linkDisplacementBounds(a, b, link_bound);
      ASSERT_EQ(link_bound.size(), robot.numLinks());
      EXPECT_LE(link_bound.maxCoeff(), bound + 1e-12);
      robot.linkPoses(a, start);
      // Points on the shapes' surfaces: box corners, the extremes of spheres and capsules along
      // their axes, the rims of cylinders' end faces.
      auto surfacePoints = [](const Shape& s) {
        std::vector<Eigen::Vector3d> points;
        const double r = s.dims.x(), h = s.kind == robots::ShapeKind::kSphere ? 0 : 0.5 * s.dims.y();
        for (int sign : {-1, 1}) {
          if (s.kind == robots::ShapeKind::kBox) {
            for (int corner = 0; corner < 4; ++corner)
              points.emplace_back((corner & 1 ? 0.5 : -0.5) * s.dims.x(), (corner & 2 ? 0.5 : -0.5) * s.dims.y(),
                                  sign * 0.5 * s.dims.z());
          } else if (s.kind == robots::ShapeKind::kCylinder) {
            for (const Eigen::Vector2d& rim : {Eigen::Vector2d(r, 0), Eigen::Vector2d(-r, 0), Eigen::Vector2d(0, r),
                                              Eigen::Vector2d(0, -r)})
              points.emplace_back(rim.x(), rim.y(), sign * h);
          } else {
            points.emplace_back(sign * r, 0, 0);
            points.emplace_back(0, sign * r, 0);
            points.emplace_back(0, 0, sign * (r + h));
          }
        }
        return points;
      };
      for (int k = 1; k <= 20; ++k) {
        robot.linkPoses(a + (k / 20.0) * (b - a), moved);
        for (int link = 0; link < robot.numLinks(); ++link)
          for (const Shape& s : robot.linkShapes(link))
            for (const Eigen::Vector3d& local : surfacePoints(s)) {
              const Eigen::Vector3d p0 = start[link] * s.pose * local, p1 = moved[link] * s.pose * local;
              const double travelled = (p1 - p0).norm();
              EXPECT_LE(travelled, (k / 20.0) * link_bound[link] + 1e-9);
              worst = std::max(worst, travelled / std::max(link_bound[link], 1e-300));
              // Seen from any link nearer the base (the self-collision pairs' bound).
              for (int base = 0; base < link; ++base) {
                const Eigen::Vector3d r0 = start[base].inverse() * p0, r1 = moved[base].inverse() * p1;
                EXPECT_LE((r1 - r0).norm(), (k / 20.0) * link_bound[link] + 1e-9);
              }
            }
      }
    }
    EXPECT_GT(worst, 0.1);  // not vacuous: motion reaches a fair share of the bound
  }
}

// Per-link bounds (Schwarzer, Saha and Latombe): a base link resting 1 mm from a wall does not make
// a wide swing of the last joint cost a bisection at the millimetre scale, as one bound and one
// distance for the whole robot would (the swing's bound over the 1 mm: hundreds of queries).
TEST(Certification, ALinkThatDoesNotMoveNeedsNoBisectionNearAnObstacle) {
  // Planar 3-link arm along +x; a box beside link 1, 1 mm below its lower edge (width 0.08).
  const auto robot = std::make_shared<robots::PlanarArm>(std::vector<double>{0.8, 0.6, 0.4}, std::vector<double>(3, 0.08),
                                                         Eigen::VectorXd::Constant(3, -kPi), Eigen::VectorXd::Constant(3, kPi));
  const auto env = std::make_shared<Environment>(std::vector<Obstacle>{box({0.4, 0.2, 0.2}, {0.4, -0.141, 0})});
  const CollisionChecker checker(robot, env);
  const ConfigurationSpace space(robot->lowerLimits(), robot->upperLimits(), Eigen::VectorXd::Ones(3));
  const CertifiedMotionValidator certified(checker, space, 0.01);
  const Eigen::Vector3d a(0, 0, 0), b(0, 0, 1.5);  // the last link swings up by 1.5 rad
  EXPECT_NEAR(checker.freeDistance(a), 0.001, 1e-4);
  EXPECT_TRUE(DiscreteMotionValidator(checker, space, 1e-4).isValid(a, b));
  ASSERT_TRUE(certified.isValid(a, b));
  EXPECT_LE(certified.distanceQueries(), 20u);
  // Moving link 1 itself towards the wall is refused (it would touch after 1 mm).
  EXPECT_FALSE(certified.isValid(a, Eigen::Vector3d(-0.05, 0, 0)));
}

// A segment that slides along a face: at 1 mm clearance it is proven (a few hundred queries); at a
// micrometre it would take about a million, so the proof stops at kMaxDistanceQueries as not valid,
// though the segment is free.
TEST(Certification, AGrazingSegmentIsNotProvenAndCostsAtMostTheQueryCap) {
  const auto robot = std::make_shared<robots::PointRobot>(Eigen::Vector2d(-5, -5), Eigen::Vector2d(5, 5));
  const auto env = std::make_shared<Environment>(std::vector<Obstacle>{box({2, 1, 1}, {0, 0, 0})});
  const CollisionChecker checker(robot, env);
  const ConfigurationSpace space(Eigen::Vector2d(-5, -5), Eigen::Vector2d(5, 5), Eigen::Vector2d(1, 1));
  const auto slide = [&](double clearance, std::uint64_t& queries) {
    const CertifiedMotionValidator certified(checker, space, 0.01);
    const double y = 0.5 + clearance;  // the face y = 0.5 plus the robot's radius
    const bool proven = certified.isValid(Eigen::Vector2d(-1, y), Eigen::Vector2d(1, y));
    queries = certified.distanceQueries();
    return proven;
  };
  std::uint64_t near = 0, grazing = 0;
  EXPECT_TRUE(slide(1e-3, near));
  EXPECT_LT(near, 5000u);
  EXPECT_FALSE(slide(2e-6, grazing));
  EXPECT_GE(grazing, static_cast<std::uint64_t>(CertifiedMotionValidator::kMaxDistanceQueries));
  EXPECT_LE(grazing, static_cast<std::uint64_t>(CertifiedMotionValidator::kMaxDistanceQueries) + 2);
  EXPECT_TRUE(DiscreteMotionValidator(checker, space, 1e-3).isValid(Eigen::Vector2d(-1, 0.5 + 2e-6),
                                                                   Eigen::Vector2d(1, 0.5 + 2e-6)));
}

// FCL's libccd GJK overestimates some distances (box-capsule by millimetres); freeDistance and
// clearance must not: against the exact box-capsule distance (min over the capsule's axis of the
// convex point-box distance, minus the radius) they are never larger, and they stay close
// (clearance to 1e-5 of it).
TEST(Certification, FreeDistanceNeverExceedsTheExactCapsuleBoxDistance) {
  robots::DhArmSpec spec;
  spec.rows = {{0, 0, 0, 0}};
  spec.lower = Eigen::VectorXd::Constant(1, -kPi);
  spec.upper = Eigen::VectorXd::Constant(1, kPi);
  spec.link_radius = {0.05};
  spec.flange = {0.6, 0, 0, 0};  // one capsule of length 0.6 along frame 1's x
  const auto robot = std::make_shared<robots::DhArm>(spec);
  const Shape& link = robot->linkShapes(0).at(0);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> unit(-1, 1);
  int compared = 0;
  robots::Poses poses;
  for (int world = 0; world < 40; ++world) {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() =
        Eigen::Quaterniond(Eigen::Vector4d(unit(rng), unit(rng), unit(rng), unit(rng)).normalized())
            .toRotationMatrix();
    pose.translation() = Eigen::Vector3d(0.6 * unit(rng), 0.6 * unit(rng), 0.2 * unit(rng));
    const Eigen::Vector3d sides(0.1 + 0.2 * (1 + unit(rng)), 0.1 + 0.2 * (1 + unit(rng)),
                                0.1 + 0.2 * (1 + unit(rng)));
    Obstacle o;
    o.shape = Shape::box(sides, pose);
    const CollisionChecker checker(robot, std::make_shared<Environment>(std::vector<Obstacle>{o}));
    for (int trial = 0; trial < 50; ++trial) {
      const Eigen::VectorXd q = Eigen::VectorXd::Constant(1, kPi * unit(rng));
      robot->linkPoses(q, poses);
      const Eigen::Isometry3d capsule = poses[0] * link.pose;
      const double exact =
          convexMin(
              [&](double s) {
                return pointBoxDistance(capsule * Eigen::Vector3d(0, 0, s), o.shape, pose);
              },
              -0.5 * link.dims.y(), 0.5 * link.dims.y()) -
          link.dims.x();
      const double d = checker.freeDistance(q);
      if (exact <= 0) {
        EXPECT_EQ(d, 0.0);
        continue;
      }
      ++compared;
      EXPECT_LE(checker.clearance(q), exact + 1e-9) << "world " << world << " q " << q[0];
      EXPECT_GE(checker.clearance(q), (1 - 1e-5) * exact - 1e-9) << "world " << world << " q " << q[0];
      EXPECT_LE(d, exact + 1e-12) << "world " << world << " q " << q[0];
      EXPECT_GE(d, 0.9 * exact - 1e-9) << "world " << world << " q " << q[0];
    }
  }
  EXPECT_GT(compared, 500);
}

// Thin coplanar boxes (planar arm links against blocks) are where FCL's box-box GJK goes wrong
// worst: 0.73 reported for 0.48 in the bench world. The exact distance of two disjoint boxes is the
// smallest distance from an edge of one to the other (convex along the edge).
TEST(Certification, FreeDistanceNeverExceedsTheExactBoxBoxDistance) {
  const int n = 6;
  const auto robot = std::make_shared<robots::PlanarArm>(
      std::vector<double>(n, 1.0), std::vector<double>(n, 0.1), Eigen::VectorXd::Constant(n, -kPi),
      Eigen::VectorXd::Constant(n, kPi));
  const auto env = std::make_shared<Environment>(std::vector<Obstacle>{
      box({1, 1, 1}, {3, 1, 0}), box({0.5, 2, 1}, {-2, 2, 0}), box({2, 0.5, 1}, {0, -3, 0})});
  const CollisionChecker checker(robot, env, /*self_collision=*/false);
  auto edgesToBox = [](const Shape& a, const Eigen::Isometry3d& pa, const Shape& b,
                       const Eigen::Isometry3d& pb) {
    double best = 1e300;
    const Eigen::Vector3d h = 0.5 * a.dims;
    for (int e = 0; e < 12; ++e) {
      const int axis = e / 4, k1 = (axis + 1) % 3, k2 = (axis + 2) % 3;
      Eigen::Vector3d p0 = -h;
      p0[k1] = e & 1 ? h[k1] : -h[k1];
      p0[k2] = e & 2 ? h[k2] : -h[k2];
      Eigen::Vector3d p1 = p0;
      p1[axis] = h[axis];
      best = std::min(
          best,
          convexMin([&](double t) { return pointBoxDistance(pa * (p0 + t * (p1 - p0)), b, pb); }, 0,
                    1));
    }
    return best;
  };
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> angle(-kPi, kPi);
  robots::Poses poses;
  int compared = 0;
  for (int trial = 0; trial < 200; ++trial) {
    Eigen::VectorXd q(n);
    for (int i = 0; i < n; ++i) q[i] = angle(rng);
    if (!checker.isValid(q)) continue;
    robot->linkPoses(q, poses);
    double exact = 1e300;
    for (int i = 0; i < n; ++i) {
      const Shape& link = robot->linkShapes(i)[0];
      const Eigen::Isometry3d pl = poses[i] * link.pose;
      for (const auto& o : env->obstacles())
        exact = std::min({exact, edgesToBox(link, pl, o.shape, o.shape.pose),
                          edgesToBox(o.shape, o.shape.pose, link, pl)});
    }
    ++compared;
    EXPECT_LE(checker.clearance(q), exact + 1e-9) << "q = [" << q.transpose() << "]";
    EXPECT_GE(checker.clearance(q), (1 - 1e-5) * exact - 1e-9) << "q = [" << q.transpose() << "]";
    const double d = checker.freeDistance(q);
    EXPECT_LE(d, exact + 1e-12) << "q = [" << q.transpose() << "]";
    EXPECT_GE(d, 0.99 * exact) << "q = [" << q.transpose() << "]";
  }
  EXPECT_GT(compared, 50);
}

// checkMotion towards an end outside the joint limits (free distance 0, yet no obstacle near): the
// proven prefix stops inside the limits, never at the end.
TEST(Certification, CheckMotionTowardsAnEndOutsideTheLimitsStopsInside) {
  const auto robot =
      std::make_shared<robots::PointRobot>(Eigen::Vector2d(-5, -5), Eigen::Vector2d(5, 5));
  const CollisionChecker checker(robot, std::make_shared<Environment>());
  const ConfigurationSpace space(Eigen::Vector2d(-5, -5), Eigen::Vector2d(5, 5),
                                 Eigen::Vector2d(1, 1));
  const CertifiedMotionValidator certified(checker, space, 0.05);
  const Eigen::Vector2d a(0, 0), b(6, 0);
  double last = -1;
  EXPECT_FALSE(certified.checkMotion(a, b, last));
  EXPECT_FALSE(certified.isValid(a, b));
  const Eigen::Vector2d reached = a + last * (b - a);
  EXPECT_TRUE(checker.isValid(reached)) << reached.transpose();
  EXPECT_GT(reached.x(), 5 - 0.05);  // pushed to within the resolution of the limit
  EXPECT_TRUE(
      certified.checkMotion(a, Eigen::Vector2d(5, 5), last));  // the corner itself is inside
  EXPECT_EQ(certified.calls(), 3u);
}

}  // namespace
}  // namespace svmp::cspace
