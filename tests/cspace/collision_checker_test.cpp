// CollisionChecker against analytic cases: which obstacle id a configuration hits, joint limits, self
// collision, virtual obstacles, the broadphase path, counters, OpenMP use and clearance.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <random>
#include <vector>

#include <fcl/narrowphase/collision.h>

#include "cspace/collision_checker.hpp"
#include "robots/dh_arm.hpp"
#include "robots/planar_arm.hpp"
#include "robots/point_robot.hpp"
#include "tests/cspace/fcl_geometry.hpp"

namespace svmp::cspace {
namespace {

using robots::Shape;
constexpr double kPi = std::numbers::pi;
// The point robot is a sphere of radius 1e-6; 1e-4 is "just inside" or "just outside" beyond that.
constexpr double kEps = 1e-4;

Eigen::Isometry3d at(double x, double y, double z = 0) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(x, y, z);
  return pose;
}

Obstacle obstacle(const Shape& shape, bool is_virtual = false) {
  Obstacle o;
  o.shape = shape;
  o.is_virtual = is_virtual;
  return o;
}

std::shared_ptr<const Environment> environment(std::vector<Obstacle> obstacles) {
  return std::make_shared<const Environment>(std::move(obstacles));
}

std::shared_ptr<const robots::Robot> point3d() {
  return std::make_shared<robots::PointRobot>(Eigen::Vector3d::Constant(-5), Eigen::Vector3d::Constant(5));
}

std::shared_ptr<const robots::PlanarArm> planarArm(std::vector<double> lengths, double width = 0.1) {
  const int n = static_cast<int>(lengths.size());
  return std::make_shared<robots::PlanarArm>(lengths, std::vector<double>(n, width),
                                             Eigen::VectorXd::Constant(n, -kPi),
                                             Eigen::VectorXd::Constant(n, kPi));
}

TEST(CollisionCheckerTest, PointRobotAgainstEachPrimitive) {
  // Box 2x2x2 at (0,0,0); sphere r=1 at (3,0,0); cylinder r=0.5 length 2 (along z) at (0,3,0); capsule
  // r=0.5 length 2 (caps add 0.5 at each end) at (0,-3,0).
  const auto env = environment({obstacle(Shape::box(Eigen::Vector3d(2, 2, 2))),
                                obstacle(Shape::sphere(1, at(3, 0))),
                                obstacle(Shape::cylinder(0.5, 2, at(0, 3))),
                                obstacle(Shape::capsule(0.5, 2, at(0, -3)))});
  const CollisionChecker checker(point3d(), env);
  struct Case {
    Eigen::Vector3d q;
    int expected;
  };
  const std::vector<Case> cases = {
      {{0, 0, 0}, 1},           {{1 - kEps, 0.5, 0.5}, 1}, {{1 + kEps, 0.5, 0.5}, kFree},
      {{3, 0, 0}, 2},           {{4 - kEps, 0, 0}, 2},     {{4 + kEps, 0, 0}, kFree},
      {{3.7, 0.7, 0}, 2},  // |(0.7, 0.7)| = 0.99 < 1
      {{0, 3, 1 - kEps}, 3},    {{0, 3, 1 + kEps}, kFree}, {{0.5 - kEps, 3, 0}, 3},
      {{0.5 + kEps, 3, 0}, kFree},
      {{0, -3, 1.5 - kEps}, 4}, {{0, -3, 1.5 + kEps}, kFree}, {{0.5 - kEps, -3, -1}, 4},
      {{0.45, -3, 1.45}, kFree},  // beside the cap: |(0.45, 0.45)| = 0.64 > 0.5
  };
  for (const auto& c : cases) {
    const int expected = c.expected;
    EXPECT_EQ(checker.check(c.q), expected) << "q = [" << c.q.transpose() << "]";
    // The analytic shapes agree (all obstacles are disjoint here).
    int analytic = kFree;
    for (const auto& o : env->obstacles())
      if (o.shape.contains(c.q)) analytic = o.id;
    EXPECT_EQ(analytic, expected) << "q = [" << c.q.transpose() << "]";
  }
}

TEST(CollisionCheckerTest, LinkEntirelyInsideABigBoxIsDetected) {
  // FCL meshes only test surfaces and would call this free; primitives must not.
  const auto arm = planarArm({1.0, 1.0});
  const CollisionChecker checker(arm, environment({obstacle(Shape::box(Eigen::Vector3d(10, 10, 10)))}));
  EXPECT_EQ(checker.check(Eigen::Vector2d(0.3, -0.5)), 1);
}

TEST(CollisionCheckerTest, ArmCrossingAThinWall) {
  // A wall 0.01 thick at x = 1.5, spanning y in [-0.5, 0.5]. Links of length 1 along x: the second link
  // spans x in [1, 2] and crosses it; folded up (q2 = pi/2) the arm stays at x <= 1.05.
  const auto arm = planarArm({1.0, 1.0});
  const CollisionChecker checker(
      arm, environment({obstacle(Shape::box(Eigen::Vector3d(0.01, 1, 1), at(1.5, 0)))}));
  EXPECT_EQ(checker.check(Eigen::Vector2d(0, 0)), 1);
  EXPECT_EQ(checker.check(Eigen::Vector2d(0, kPi / 2)), kFree);
  EXPECT_EQ(checker.check(Eigen::Vector2d(kPi / 2, 0)), kFree);
}

TEST(CollisionCheckerTest, LowestIdWinsAndVirtualObstaclesMayBeTouched) {
  // Obstacle 1 is virtual and covers the tip; 2 is far away; 3 and 4 both overlap link 1.
  const auto arm = planarArm({1.0, 1.0});
  const auto env = environment({obstacle(Shape::sphere(0.2, at(2, 0)), true),
                                obstacle(Shape::sphere(0.2, at(-3, -3))),
                                obstacle(Shape::sphere(0.2, at(0.6, 0))),
                                obstacle(Shape::sphere(0.2, at(0.3, 0)))});
  const CollisionChecker checker(arm, env);
  const Eigen::Vector2d q(0, 0);
  EXPECT_EQ(checker.check(q), 3);
  EXPECT_EQ(checker.checkIncludingVirtual(q), 1);
  EXPECT_TRUE(checker.hits(q, 1));
  EXPECT_FALSE(checker.hits(q, 2));
  EXPECT_TRUE(checker.hits(q, 4));
  // Pointing up (x in [-0.05, 0.05]) the arm clears the sphere at (0.3, 0) by 0.05.
  EXPECT_EQ(checker.check(Eigen::Vector2d(kPi / 2, 0)), kFree);
  // Only the virtual obstacle: check() says free, the others see it.
  const CollisionChecker only_virtual(arm, environment({obstacle(Shape::sphere(0.2, at(2, 0)), true)}));
  EXPECT_EQ(only_virtual.check(q), kFree);
  EXPECT_TRUE(only_virtual.isValid(q));
  EXPECT_EQ(only_virtual.checkIncludingVirtual(q), 1);
  EXPECT_DOUBLE_EQ(only_virtual.clearance(q), std::numeric_limits<double>::infinity());
}

// Environment::nestedGroups: a shape given twice, a box inside a turned box, a sphere inside a box and
// a chain of nested boxes join; the four boxes of a frame round a window, which overlap at its
// corners, a box that pokes out of another, a small box in a corner of a turned box's bounding box
// but outside the box, and a sphere half out of another stay apart, as do virtual obstacles.
TEST(EnvironmentTest, NestedObstaclesFormOneGroupAndAFramesPiecesDoNot) {
  Eigen::Isometry3d turned = at(5, 5);
  turned.linear() = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  // Just inside the corner of 3's bounding box nearest its lowest point: outside the turned box.
  const Shape big = Shape::box(Eigen::Vector3d(2, 2, 2), turned);
  const Eigen::Isometry3d corner = at(big.bounds().min().x() + 0.05, big.bounds().min().y() + 0.05,
                                      big.bounds().min().z() + 0.05);
  const Environment env({
      obstacle(Shape::box(Eigen::Vector3d(1, 1, 1), at(0, 0))),              // 1
      obstacle(Shape::box(Eigen::Vector3d(1, 1, 1), at(0, 0))),              // 2: 1 again
      obstacle(Shape::box(Eigen::Vector3d(2, 2, 2), turned)),                 // 3
      obstacle(Shape::box(Eigen::Vector3d(0.5, 0.5, 0.5), turned)),           // 4: inside 3
      obstacle(Shape::sphere(0.4, at(5.2, 5.1))),                             // 5: inside 3
      obstacle(Shape::box(Eigen::Vector3d(0.2, 3, 1), at(-10, 0))),          // 6-9: a frame
      obstacle(Shape::box(Eigen::Vector3d(0.2, 3, 1), at(-8, 0))),
      obstacle(Shape::box(Eigen::Vector3d(2.2, 0.2, 1), at(-9, 1.4))),
      obstacle(Shape::box(Eigen::Vector3d(2.2, 0.2, 1), at(-9, -1.4))),
      obstacle(Shape::box(Eigen::Vector3d(1, 1, 1), at(10, 0))),             // 10
      obstacle(Shape::box(Eigen::Vector3d(0.5, 0.5, 0.5), at(10.4, 0))),     // 11: pokes out of 10
      obstacle(Shape::box(Eigen::Vector3d(0.5, 0.5, 0.5), at(0.1, 0)), true),  // 12: virtual, inside 1
      obstacle(Shape::box(Eigen::Vector3d(0.6, 0.6, 0.6), at(0.1, 0))),      // 13: inside 1
      obstacle(Shape::box(Eigen::Vector3d(0.3, 0.3, 0.3), at(0.15, 0))),     // 14: inside 13
      obstacle(Shape::box(Eigen::Vector3d(0.05, 0.05, 0.05), corner)),         // 15: beside 3
      obstacle(Shape::sphere(1, at(20, 0))),                                  // 16
      obstacle(Shape::sphere(0.5, at(20.8, 0))),                              // 17: half out of 16
  });
  EXPECT_EQ(env.nestedGroups(), (std::vector<int>{1, 1, 3, 3, 3, 6, 7, 8, 9, 10, 11, 12, 1, 1, 15, 16, 17}));
  // Inside another kept one: 2 (1 again), 13 and 14 (in 1), 4 and 5 (in 3); the virtual 12 is no member.
  EXPECT_EQ(env.innerObstacles(env.nestedGroups()),
            (std::vector<char>{0, 1, 0, 1, 1, 0, 0, 0, 0, 0, 0, 0, 1, 1, 0, 0, 0}));
  // The small box is in 3's bounding box, so only the test of the shapes keeps it apart.
  const Eigen::AlignedBox3d bounds = env.byId(3).shape.bounds();
  EXPECT_TRUE(bounds.contains(env.byId(15).shape.bounds()));
  EXPECT_FALSE(env.byId(3).shape.contains(corner.translation()));
}

TEST(CollisionCheckerTest, JointLimitsComeFirst) {
  const auto arm = planarArm({1.0, 1.0});
  const CollisionChecker checker(arm, environment({obstacle(Shape::box(Eigen::Vector3d(10, 10, 10)))}));
  EXPECT_EQ(checker.check(Eigen::Vector2d(kPi + 0.01, 0)), kJointLimitHit);
  EXPECT_EQ(checker.check(Eigen::Vector2d(0, std::nan(""))), kJointLimitHit);
  EXPECT_FALSE(checker.hits(Eigen::Vector2d(kPi + 0.01, 0), 1));
  // A configuration of the wrong size is a caller error, not a joint-limit hit.
  EXPECT_THROW(checker.check(Eigen::Vector3d(0, 0, 0)), std::invalid_argument);
  EXPECT_THROW(checker.hits(Eigen::VectorXd::Zero(1), 1), std::invalid_argument);
  EXPECT_THROW(checker.clearance(Eigen::Vector3d(0, 0, 0)), std::invalid_argument);
}

TEST(CollisionCheckerTest, FoldedPlanarArmCollidesWithItself) {
  // Links of length 1: link 1 along +x, link 2 back at 172 degrees to (0.01, 0.14), link 3 at 344
  // degrees runs back across link 1 near x = 0.5.
  const auto arm = planarArm({1.0, 1.0, 1.0});
  const CollisionChecker checker(arm, environment({}));
  EXPECT_EQ(checker.selfCollisionPairs(), (std::vector<std::pair<int, int>>{{0, 2}}));
  EXPECT_EQ(checker.check(Eigen::Vector3d(0, 3.0, 3.0)), kSelfCollisionHit);
  EXPECT_EQ(checker.check(Eigen::Vector3d(0, 0.5, 0.5)), kFree);
  const CollisionChecker no_self(arm, environment({}), false);
  EXPECT_EQ(no_self.check(Eigen::Vector3d(0, 3.0, 3.0)), kFree);
}

TEST(CollisionCheckerTest, DhArmsAreNotSelfCollidingInNormalPoses) {
  const auto crs = std::make_shared<robots::DhArm>(robots::crsF3Spec(6));
  const CollisionChecker crs_checker(crs, environment({}));
  EXPECT_EQ(crs_checker.check(Eigen::VectorXd::Zero(6)), kFree);

  const auto panda = std::make_shared<robots::DhArm>(robots::pandaSpec());
  const CollisionChecker panda_checker(panda, environment({}));
  Eigen::VectorXd ready(7);
  ready << 0, -kPi / 4, 0, -3 * kPi / 4, 0, kPi / 2, kPi / 4;
  EXPECT_EQ(panda_checker.check(ready), kFree);
  // Link 4's capsule ends at the wrist (radius 0.055) and link 7's starts 0.088 further on (radius
  // 0.04): they always touch, so the filter must have dropped that pair.
  const auto all = panda->nonAdjacentLinkPairs();
  const auto& kept = panda_checker.selfCollisionPairs();
  EXPECT_NE(std::find(all.begin(), all.end(), std::make_pair(3, 6)), all.end());
  EXPECT_EQ(std::find(kept.begin(), kept.end(), std::make_pair(3, 6)), kept.end());
  EXPECT_LT(kept.size(), all.size());
}

// The least distance between two segments, by brute force over 101 points on each.
double segmentDistance(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1, const Eigen::Vector3d& b0,
                       const Eigen::Vector3d& b1) {
  double best = INFINITY;
  for (int i = 0; i <= 100; ++i)
    for (int j = 0; j <= 100; ++j)
      best = std::min(best, ((a0 + (a1 - a0) * (i / 100.0)) - (b0 + (b1 - b0) * (j / 100.0))).norm());
  return best;
}

TEST(CollisionCheckerTest, DhBaseColumnMeetsFoldedLinksAsCapsuleDistancesSay) {
  // Every DH shape here is a capsule (no tool): a base-link pair collides when the axes come closer
  // than the radii's sum. Configurations within 5 mm of contact are left out (the brute force's
  // error is under 3 mm); some must hit the column and nothing else, or the column would go unseen.
  for (const auto& spec : {robots::pandaSpec(), robots::crsF3Spec(6)}) {
    const auto arm = std::make_shared<robots::DhArm>(spec);
    const CollisionChecker checker(arm, environment({}));
    ASSERT_FALSE(arm->baseShapes().empty());
    const auto ends = [](const Shape& s, const Eigen::Isometry3d& at) {
      return std::make_pair(at * (s.pose * Eigen::Vector3d(0, 0, -0.5 * s.dims.y())),
                            at * (s.pose * Eigen::Vector3d(0, 0, 0.5 * s.dims.y())));
    };
    std::mt19937_64 rng(11);
    Eigen::VectorXd q(arm->dof());
    robots::Poses poses;
    int column_only = 0, decided = 0;
    for (int n = 0; n < 1500; ++n) {
      for (int i = 0; i < q.size(); ++i)
        q[i] = std::uniform_real_distribution<double>(arm->lowerLimits()[i], arm->upperLimits()[i])(rng);
      arm->linkPoses(q, poses);
      bool near_contact = false, column_hit = false, other_hit = false;
      for (const auto& [a, b] : checker.selfCollisionPairs())
        for (const Shape& sb : arm->linkShapes(b))
          for (const Shape& sa : a == robots::Robot::kBase ? arm->baseShapes() : arm->linkShapes(a)) {
            const auto [a0, a1] = ends(sa, a == robots::Robot::kBase ? Eigen::Isometry3d::Identity() : poses[a]);
            const auto [b0, b1] = ends(sb, poses[b]);
            const double gap = segmentDistance(a0, a1, b0, b1) - sa.dims.x() - sb.dims.x();
            near_contact = near_contact || std::abs(gap) < 5e-3;
            (a == robots::Robot::kBase ? column_hit : other_hit) |= gap < 0;
          }
      if (near_contact) continue;
      ++decided;
      EXPECT_EQ(checker.check(q) == kSelfCollisionHit, column_hit || other_hit) << spec.name << " q " << q.transpose();
      column_only += column_hit && !other_hit;
    }
    EXPECT_GT(decided, 1000) << spec.name;
    EXPECT_GT(column_only, 3) << spec.name;  // 7 and 8 of 1,500
  }
}

TEST(CollisionCheckerTest, AToolOffsetFromJointOneMeetsTheBaseColumn) {
  // A pan-tilt head on a 0.5 m post: two joints at the post's top, no link segment, only a tool box
  // 0.2-0.5 m out along the flange's x. Tilted down (q2 = -pi/2) the box runs along the post. The
  // tool's link is the first with a shape, yet it must be checked against the base.
  robots::DhArmSpec spec;
  spec.rows = {{0, 0, 0.5, 0}, {0, std::numbers::pi / 2, 0, 0}};
  spec.lower = Eigen::Vector2d(-kPi, -kPi);
  spec.upper = Eigen::Vector2d(kPi, kPi);
  spec.link_radius = {0.05, 0.03};
  spec.tool = {Shape::box(Eigen::Vector3d(0.3, 0.05, 0.05), Eigen::Isometry3d(Eigen::Translation3d(0.35, 0, 0)))};
  const auto head = std::make_shared<robots::DhArm>(spec);
  const CollisionChecker checker(head, environment({}));
  EXPECT_EQ(checker.selfCollisionPairs(), (std::vector<std::pair<int, int>>{{robots::Robot::kBase, 1}}));
  EXPECT_TRUE(checker.droppedSelfCollisionPairs().empty());
  EXPECT_EQ(checker.check(Eigen::Vector2d(0, -kPi / 2)), kSelfCollisionHit);
  EXPECT_EQ(checker.check(Eigen::Vector2d(0, 0)), kFree);
  EXPECT_EQ(checker.check(Eigen::Vector2d(1, kPi / 2)), kFree);  // tilted up, away from the post
  // The Panda's upper arm starts at joint 1's origin, on the column's cap: that pair is dropped
  // without being listed as a surprise.
  const CollisionChecker panda(std::make_shared<robots::DhArm>(robots::pandaSpec()), environment({}));
  for (const auto& pair : panda.droppedSelfCollisionPairs()) EXPECT_NE(pair.first, robots::Robot::kBase);
}

TEST(CollisionCheckerTest, BroadphaseAgreesWithPerObstacleTests) {
  // 14 obstacles (> 8) go through the broadphase grid; hits() tests each obstacle on its own, and
  // allHits() names every one hit.
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> coord(-2.5, 2.5), size(0.05, 0.3);
  std::vector<Obstacle> obstacles;
  for (int i = 0; i < 14; ++i) {
    const Shape shape = i % 2 ? Shape::sphere(size(rng), at(coord(rng), coord(rng)))
                              : Shape::box(Eigen::Vector3d(size(rng), size(rng), 1),
                                           at(coord(rng), coord(rng)));
    obstacles.push_back(obstacle(shape, i == 5));
  }
  const auto env = environment(std::move(obstacles));
  const auto arm = planarArm({1.0, 0.8, 0.6});
  const CollisionChecker checker(arm, env, false);
  std::uniform_real_distribution<double> angle(-kPi, kPi);
  int hit = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const Eigen::Vector3d q(angle(rng), angle(rng), angle(rng));
    int expected = kFree, expected_virtual = kFree;
    std::vector<int> all, all_real;  // allHits: every id hit, ascending
    for (int id = env->size(); id >= 1; --id) {
      if (!checker.hits(q, id)) continue;
      expected_virtual = id;
      all.insert(all.begin(), id);
      if (env->byId(id).is_virtual) continue;
      expected = id;
      all_real.insert(all_real.begin(), id);
    }
    EXPECT_EQ(checker.check(q), expected) << "q = [" << q.transpose() << "]";
    EXPECT_EQ(checker.checkIncludingVirtual(q), expected_virtual) << "q = [" << q.transpose() << "]";
    EXPECT_EQ(checker.allHits(q, true), all) << "q = [" << q.transpose() << "]";
    EXPECT_EQ(checker.allHits(q, false), all_real) << "q = [" << q.transpose() << "]";
    EXPECT_EQ(checker.ValidityChecker::allHits(q, true), all) << "the default, hits() by hits()";
    hit += expected != kFree;
  }
  EXPECT_GT(hit, 30);  // the comparison covers both answers
  EXPECT_LT(hit, 270);
}

// The whole check (the checker's own bounding boxes, then its GJK or the separating-axis test)
// against FCL's collide on every pair, placed from the robot's link poses: the Panda's capsules and
// a planar arm's boxes among boards, random configurations, a fifth to a half of them colliding.
TEST(CollisionCheckerTest, ArmsAgreeWithFclOnEveryPair) {
  const auto board = [](Eigen::Vector3d sides, Eigen::Vector3d centre) {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translation() = centre;
    pose.linear() = Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
    return obstacle(Shape::box(sides, pose));
  };
  const std::vector<std::shared_ptr<const robots::Robot>> robots = {
      std::make_shared<robots::DhArm>(robots::pandaSpec()), planarArm({1.0, 0.8, 0.6, 0.5}, 0.05)};
  const auto env = environment({board({0.6, 0.4, 0.03}, {0.5, 0.1, 0.3}), board({0.05, 0.8, 0.8}, {-0.4, 0.3, 0.4}),
                                board({1.2, 0.1, 1.0}, {0.2, -1.0, 0.2})});
  std::mt19937_64 rng(17);
  for (const auto& robot : robots) {
    const CollisionChecker checker(robot, env, false);
    std::vector<std::shared_ptr<fcl::CollisionObjectd>> obstacles;
    for (const auto& o : env->obstacles())
      obstacles.push_back(std::make_shared<fcl::CollisionObjectd>(test::fclGeometry(o.shape), o.shape.pose.linear(),
                                                                  o.shape.pose.translation()));
    int colliding = 0;
    robots::Poses poses;
    for (int trial = 0; trial < 2000; ++trial) {
      Eigen::VectorXd q(robot->dof());
      for (int i = 0; i < q.size(); ++i)
        q[i] = std::uniform_real_distribution<double>(robot->lowerLimits()[i], robot->upperLimits()[i])(rng);
      robot->linkPoses(q, poses);
      bool fcl_hit = false;
      for (int i = 0; i < robot->numLinks() && !fcl_hit; ++i)
        for (const Shape& part : robot->linkShapes(i)) {
          const Eigen::Isometry3d world = poses[i] * part.pose;
          const fcl::CollisionObjectd link(test::fclGeometry(part), world.linear(), world.translation());
          for (const auto& o : obstacles) {
            fcl::CollisionRequestd request;
            fcl::CollisionResultd result;
            fcl_hit = fcl_hit || fcl::collide(&link, o.get(), request, result) > 0;
          }
        }
      EXPECT_EQ(checker.check(q) != kFree, fcl_hit) << "dof " << robot->dof() << ", trial " << trial;
      colliding += fcl_hit;
    }
    EXPECT_GT(colliding, 2000 / 5) << "dof " << robot->dof();
    EXPECT_LT(colliding, 2000 / 2) << "dof " << robot->dof();
  }
}

TEST(CollisionCheckerTest, CountersCountEveryConfigurationTested) {
  const CollisionChecker checker(point3d(), environment({obstacle(Shape::sphere(1))}));
  EXPECT_EQ(checker.collisionChecks(), 0u);
  checker.check(Eigen::Vector3d(0, 0, 0));
  checker.isValid(Eigen::Vector3d(2, 0, 0));
  checker.checkIncludingVirtual(Eigen::Vector3d(2, 0, 0));
  checker.hits(Eigen::Vector3d(2, 0, 0), 1);
  checker.check(Eigen::Vector3d(9, 0, 0));  // outside the limits still counts
  checker.clearance(Eigen::Vector3d(2, 0, 0));  // a distance query, not a check
  EXPECT_EQ(checker.collisionChecks(), 5u);
  EXPECT_EQ(checker.distanceQueries(), 1u);
}

TEST(CollisionCheckerTest, OpenMpThreadsGiveTheSerialAnswers) {
  std::vector<Obstacle> obstacles;
  for (int i = 0; i < 12; ++i)  // broadphase path
    obstacles.push_back(obstacle(Shape::sphere(0.3, at(std::cos(i) * 1.5, std::sin(i) * 1.5))));
  const auto arm = planarArm({1.0, 0.8, 0.6});
  const CollisionChecker checker(arm, environment(std::move(obstacles)));
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> angle(-kPi, kPi);
  constexpr int kConfigs = 2000;
  Eigen::Matrix3Xd configs(3, kConfigs);
  for (int i = 0; i < kConfigs; ++i) configs.col(i) = Eigen::Vector3d(angle(rng), angle(rng), angle(rng));
  std::vector<int> serial(kConfigs), parallel(kConfigs);
  for (int i = 0; i < kConfigs; ++i) serial[i] = checker.check(configs.col(i));
  const std::uint64_t before = checker.collisionChecks();
#pragma omp parallel for num_threads(4) schedule(dynamic, 16)
  for (int i = 0; i < kConfigs; ++i) parallel[i] = checker.check(configs.col(i));
  EXPECT_EQ(parallel, serial);
  EXPECT_EQ(checker.collisionChecks() - before, static_cast<std::uint64_t>(kConfigs));
}

TEST(CollisionCheckerTest, ClearanceMatchesHandComputedDistances) {
  // Point at the origin, box of side 2 centred at (3, 0, 0): 2 to its face, less the 1e-6 radius.
  const CollisionChecker point(point3d(), environment({obstacle(Shape::box(Eigen::Vector3d(2, 2, 2),
                                                                           at(3, 0)))}));
  EXPECT_NEAR(point.clearance(Eigen::Vector3d(0, 0, 0)), 2.0, 1e-5);
  EXPECT_NEAR(point.clearance(Eigen::Vector3d(0, 3, 0)), std::hypot(2.0, 2.0), 1e-5);  // to (2, 1, 0)
  EXPECT_EQ(point.clearance(Eigen::Vector3d(3, 0, 0)), 0.0);
  // A link from (0,0) to (1,0), 0.1 wide (top face y = 0.05); sphere of radius 0.2 at (0.5, 1):
  // 1 - 0.05 - 0.2 = 0.75. A second, farther obstacle does not change the minimum.
  const auto arm = planarArm({1.0});
  const CollisionChecker link(arm, environment({obstacle(Shape::sphere(0.2, at(0.5, 1))),
                                                obstacle(Shape::sphere(0.2, at(-3, 0)))}));
  EXPECT_NEAR(link.clearance(Eigen::VectorXd::Zero(1)), 0.75, 1e-5);
}

TEST(CollisionCheckerTest, RejectsMissingInputs) {
  EXPECT_THROW(CollisionChecker(nullptr, environment({})), std::invalid_argument);
  EXPECT_THROW(CollisionChecker(point3d(), nullptr), std::invalid_argument);
  EXPECT_THROW(environment({obstacle(Shape::sphere(-1))}), std::invalid_argument);
}

}  // namespace
}  // namespace svmp::cspace
