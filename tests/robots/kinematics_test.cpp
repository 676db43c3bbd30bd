// Forward kinematics and control points against poses computed by hand (not by re-running the code).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "robots/dh_arm.hpp"
#include "robots/planar_arm.hpp"
#include "robots/point_robot.hpp"

namespace svmp::robots {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kTol = 1e-12;

// A configuration drawn uniformly within the robot's joint limits, joint by joint.
Eigen::VectorXd randomConfiguration(const Robot& robot, std::mt19937_64& rng) {
  Eigen::VectorXd q(robot.dof());
  for (int k = 0; k < q.size(); ++k)
    q[k] = std::uniform_real_distribution<double>(robot.lowerLimits()[k], robot.upperLimits()[k])(rng);
  return q;
}

void expectNear(const Eigen::Vector3d& actual, const Eigen::Vector3d& expected, const char* what) {
  EXPECT_LT((actual - expected).norm(), kTol)
      << what << ": got [" << actual.transpose() << "], expected [" << expected.transpose() << "]";
}

Eigen::VectorXd vec(std::initializer_list<double> values) {
  Eigen::VectorXd v(values.size());
  int i = 0;
  for (double x : values) v[i++] = x;
  return v;
}

PlanarArm threeLinkArm() {
  return PlanarArm({1.0, 0.5, 0.25}, {0.1, 0.1, 0.1}, Eigen::VectorXd::Constant(3, -kPi),
                   Eigen::VectorXd::Constant(3, kPi), Eigen::Vector2d(0.5, -1));
}

TEST(PointRobotTest, PoseAndControlPointAreThePosition) {
  PointRobot robot(Eigen::Vector2d(0, 0), Eigen::Vector2d(10, 10));
  EXPECT_EQ(robot.name(), "point2d");
  EXPECT_EQ(robot.workspaceDim(), 2);
  Poses poses;
  robot.linkPoses(Eigen::Vector2d(3, 4), poses);
  ASSERT_EQ(poses.size(), 1u);
  expectNear(poses[0].translation(), Eigen::Vector3d(3, 4, 0), "point");
  Eigen::Matrix3Xd points;
  robot.controlPoints(Eigen::Vector2d(3, 4), points);
  ASSERT_EQ(points.cols(), 1);
  expectNear(points.col(0), Eigen::Vector3d(3, 4, 0), "control point");
  EXPECT_THROW(PointRobot(Eigen::VectorXd::Zero(1), Eigen::VectorXd::Ones(1)), std::invalid_argument);
  EXPECT_THROW(PointRobot(Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 1), 0.0), std::invalid_argument);
}

TEST(PlanarArmTest, JointsAndTipByTrigonometry) {
  const PlanarArm arm = threeLinkArm();
  // q = (pi/2, -pi/2, 3pi/4): absolute link angles pi/2, 0, 3pi/4. From the base (0.5, -1): joint 2 at
  // (0.5, 0), joint 3 at (1.0, 0), tip at (1.0 - 0.25/sqrt2, 0.25/sqrt2).
  const Eigen::VectorXd q = vec({kPi / 2, -kPi / 2, 3 * kPi / 4});
  const double r = 0.25 / std::sqrt(2.0);
  Poses poses;
  arm.linkPoses(q, poses);
  ASSERT_EQ(poses.size(), 3u);
  expectNear(poses[0].translation(), Eigen::Vector3d(0.5, -1, 0), "joint 1");
  expectNear(poses[1].translation(), Eigen::Vector3d(0.5, 0, 0), "joint 2");
  expectNear(poses[2].translation(), Eigen::Vector3d(1.0, 0, 0), "joint 3");
  // Each link frame's x axis points along its link.
  expectNear(poses[0].linear().col(0), Eigen::Vector3d(0, 1, 0), "link 1 axis");
  expectNear(poses[2].linear().col(0), Eigen::Vector3d(-std::sqrt(0.5), std::sqrt(0.5), 0), "link 3 axis");

  Eigen::Matrix3Xd points;
  arm.controlPoints(q, points);
  ASSERT_EQ(points.cols(), 3);  // joints 2, 3 and the tip: joint 1 never moves
  expectNear(points.col(0), Eigen::Vector3d(0.5, 0, 0), "control point joint 2");
  expectNear(points.col(1), Eigen::Vector3d(1.0, 0, 0), "control point joint 3");
  expectNear(points.col(2), Eigen::Vector3d(1.0 - r, r, 0), "control point tip");
  EXPECT_EQ(arm.numControlPoints(), 3);
  const Eigen::Vector2d mid = arm.pointOnLink(q, 2, 0.125);
  EXPECT_LT((mid - Eigen::Vector2d(1.0 - r / 2, r / 2)).norm(), kTol);
}

TEST(PlanarArmTest, LinkShapesAreBoxesFromJointToJoint) {
  const PlanarArm arm = threeLinkArm();
  Poses poses;
  const Eigen::VectorXd q = vec({0.3, -1.2, 2.0});
  arm.linkPoses(q, poses);
  for (int i = 0; i < 3; ++i) {
    ASSERT_EQ(arm.linkShapes(i).size(), 1u);
    const Shape& box = arm.linkShapes(i)[0];
    EXPECT_EQ(box.kind, ShapeKind::kBox);
    // In the link frame the box spans x in [0, length].
    const double length = arm.lengths()[i];
    EXPECT_TRUE(box.contains(Eigen::Vector3d(length - 1e-9, 0, 0)));
    EXPECT_FALSE(box.contains(Eigen::Vector3d(length + 1e-9, 0, 0)));
    EXPECT_FALSE(box.contains(Eigen::Vector3d(-1e-9, 0, 0)));
  }
  EXPECT_THROW(PlanarArm({1.0, -1.0}, {0.1, 0.1}, Eigen::Vector2d(-1, -1), Eigen::Vector2d(1, 1)),
               std::invalid_argument);
  EXPECT_THROW(PlanarArm({1.0, 1.0}, {0.1}, Eigen::Vector2d(-1, -1), Eigen::Vector2d(1, 1)),
               std::invalid_argument);
}

// CRS-F3, thesis Table 4.3, modified DH: frame i = frame i-1 RotX(alpha) TransX(a) RotZ(theta) TransZ(d).
//
// q = 0. Frame 1: origin (0, 0, 0.35), axes = world. Frame 2: RotX(pi/2) TransX(0.1) RotZ(pi/2) gives
// origin (0.1, 0, 0.35) and axes x2 = RotX(pi/2)(0,1,0) = (0,0,1), y2 = RotX(pi/2)(-1,0,0) = (-1,0,0),
// z2 = RotX(pi/2)(0,0,1) = (0,-1,0): the upper arm points up. Frame 3: 0.265 along x2 -> elbow at
// (0.1, 0, 0.615), axes as frame 2. Frame 4: RotX(pi/2) turns z into -y3 = (1,0,0); TransZ(0.27) ->
// wrist centre (0.37, 0, 0.615). Frame 5 = frame 4 RotX(-pi/2): axes of frame 3 again. Frame 6: z6 =
// -y5 = (1,0,0); TransZ(0.075) -> flange (0.445, 0, 0.615).
//
// q1 = pi/2 turns all of it about the world z axis: (x, y, z) -> (-y, x, z).
//
// q = (0, 0, pi/2, 0, pi/2, 0). Frame 3 = frame 2 RotZ(pi/2): x3 = y2 = (-1,0,0), y3 = -x2 = (0,0,-1);
// the forearm runs along -y3 = (0,0,1): wrist at (0.1, 0, 0.885). Frame 5 = frame 3 RotZ(pi/2) (the
// RotX(pi/2) RotX(-pi/2) cancel): y5 = R3 (-1,0,0) = -x3 = (1,0,0); z6 = -y5 = (-1,0,0): flange at
// (0.025, 0, 0.885).
//
// q = (0, pi/2, 0, 0, 0, 0). Frame 2 = RotX(pi/2) RotZ(pi): x2 = (-1,0,0), y2 = (0,0,-1). Elbow at
// (0.1 - 0.265, 0, 0.35); forearm along -y3 = (0,0,1): wrist (-0.165, 0, 0.62); z6 = -y3: flange
// (-0.165, 0, 0.695).
struct CrsCase {
  Eigen::VectorXd q;
  Eigen::Vector3d shoulder, elbow, wrist, flange;
};

TEST(DhArmTest, CrsF3PosesMatchHandDerivation) {
  const DhArm arm(crsF3Spec(6));
  const std::vector<CrsCase> cases = {
      {vec({0, 0, 0, 0, 0, 0}), {0.1, 0, 0.35}, {0.1, 0, 0.615}, {0.37, 0, 0.615}, {0.445, 0, 0.615}},
      {vec({kPi / 2, 0, 0, 0, 0, 0}), {0, 0.1, 0.35}, {0, 0.1, 0.615}, {0, 0.37, 0.615},
       {0, 0.445, 0.615}},
      {vec({0, 0, kPi / 2, 0, kPi / 2, 0}), {0.1, 0, 0.35}, {0.1, 0, 0.615}, {0.1, 0, 0.885},
       {0.025, 0, 0.885}},
      {vec({0, kPi / 2, 0, 0, 0, 0}), {0.1, 0, 0.35}, {-0.165, 0, 0.35}, {-0.165, 0, 0.62},
       {-0.165, 0, 0.695}},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(::testing::Message() << "q = [" << c.q.transpose() << "]");
    Poses poses;
    arm.linkPoses(c.q, poses);
    ASSERT_EQ(poses.size(), 6u);
    expectNear(poses[0].translation(), Eigen::Vector3d(0, 0, 0.35), "frame 1");
    expectNear(poses[1].translation(), c.shoulder, "frame 2");
    expectNear(poses[2].translation(), c.elbow, "frame 3");
    expectNear(poses[3].translation(), c.wrist, "frame 4");
    expectNear(poses[4].translation(), c.wrist, "frame 5");
    expectNear(poses[5].translation(), c.flange, "frame 6");
    expectNear(arm.flangePose(c.q).translation(), c.flange, "flange");

    // Control points: the distinct moving joint origins (frames 2, 3, 4) and the tool tip.
    Eigen::Matrix3Xd points;
    arm.controlPoints(c.q, points);
    ASSERT_EQ(points.cols(), 4);
    expectNear(points.col(0), c.shoulder, "control point frame 2");
    expectNear(points.col(1), c.elbow, "control point frame 3");
    expectNear(points.col(2), c.wrist, "control point wrist");
    expectNear(points.col(3), c.flange, "control point tip");
  }
}

TEST(DhArmTest, CrsF3SimplifiedModelEndsAtTheWristCentre) {
  const DhArm arm(crsF3Spec(3));
  EXPECT_EQ(arm.dof(), 3);
  expectNear(arm.flangePose(vec({0, 0, 0})).translation(), Eigen::Vector3d(0.37, 0, 0.615), "wrist");
  expectNear(arm.flangePose(vec({0, 0, kPi / 2})).translation(), Eigen::Vector3d(0.1, 0, 0.885),
             "wrist, elbow up");
  Eigen::Matrix3Xd points;
  arm.controlPoints(vec({0, 0, 0}), points);
  ASSERT_EQ(points.cols(), 3);  // frames 2, 3 and the wrist centre
  expectNear(points.col(2), Eigen::Vector3d(0.37, 0, 0.615), "tip");
  EXPECT_THROW(crsF3Spec(4), std::invalid_argument);
}

TEST(DhArmTest, CrsF3ToolTipIsInTheFlangeFrame) {
  DhArmSpec spec = crsF3Spec(6);
  spec.tool_tip = Eigen::Vector3d(0, 0, 0.1);  // 0.1 further along the flange's z = world x at q = 0
  spec.tool = {Shape::box(Eigen::Vector3d(0.05, 0.05, 0.05))};
  const DhArm arm(spec);
  Eigen::Matrix3Xd points;
  arm.controlPoints(Eigen::VectorXd::Zero(6), points);
  ASSERT_EQ(points.cols(), 7);  // frame 6's origin is now distinct from the tip; then the box's two ends
  expectNear(points.col(3), Eigen::Vector3d(0.445, 0, 0.615), "frame 6");
  expectNear(points.col(4), Eigen::Vector3d(0.545, 0, 0.615), "tool tip");
  expectNear(arm.flangePose(Eigen::VectorXd::Zero(6)).inverse() * points.col(5), Eigen::Vector3d(0.025, 0, 0), "box end");
  expectNear(arm.flangePose(Eigen::VectorXd::Zero(6)).inverse() * points.col(6), Eigen::Vector3d(-0.025, 0, 0), "box end");
  EXPECT_EQ(arm.linkShapes(5).size(), 1u);
}

// Panda (modified DH, pandaSpec). q = 0: frame 1 (0,0,0.333); frame 2 = RotX(-pi/2), same origin;
// frame 3 = RotX(pi/2) TransZ(0.316): axes = world, origin (0,0,0.649); frame 4 = RotX(pi/2)
// TransX(0.0825): (0.0825,0,0.649); frame 5 = RotX(-pi/2) TransX(-0.0825) TransZ(0.384): axes = world,
// origin (0,0,1.033); frame 6 = RotX(pi/2), same origin; frame 7 = RotX(pi/2) TransX(0.088): origin
// (0.088,0,1.033), rotation RotX(pi) so z7 = (0,0,-1); flange = TransZ(0.107): (0.088, 0, 0.926).
TEST(DhArmTest, PandaAtZeroMatchesHandDerivation) {
  const DhArm arm(pandaSpec());
  const Eigen::VectorXd q = Eigen::VectorXd::Zero(7);
  Poses poses;
  arm.linkPoses(q, poses);
  ASSERT_EQ(poses.size(), 7u);
  expectNear(poses[2].translation(), Eigen::Vector3d(0, 0, 0.649), "frame 3");
  expectNear(poses[3].translation(), Eigen::Vector3d(0.0825, 0, 0.649), "frame 4");
  expectNear(poses[4].translation(), Eigen::Vector3d(0, 0, 1.033), "frame 5");
  expectNear(poses[6].translation(), Eigen::Vector3d(0.088, 0, 1.033), "frame 7");
  const Eigen::Isometry3d flange = arm.flangePose(q);
  expectNear(flange.translation(), Eigen::Vector3d(0.088, 0, 0.926), "flange");
  expectNear(flange.linear().col(2), Eigen::Vector3d(0, 0, -1), "flange z");

  Eigen::Matrix3Xd points;
  arm.controlPoints(q, points);
  ASSERT_EQ(points.cols(), 5);  // frames 3, 4, 5, 7 and the flange
  expectNear(points.col(0), Eigen::Vector3d(0, 0, 0.649), "cp frame 3");
  expectNear(points.col(1), Eigen::Vector3d(0.0825, 0, 0.649), "cp frame 4");
  expectNear(points.col(2), Eigen::Vector3d(0, 0, 1.033), "cp frame 5");
  expectNear(points.col(3), Eigen::Vector3d(0.088, 0, 1.033), "cp frame 7");
  expectNear(points.col(4), Eigen::Vector3d(0.088, 0, 0.926), "cp flange");
}

// Panda, q2 = 0.7: joint 2's axis at q = 0 is z2 = RotX(-pi/2) (0,0,1) = (0,1,0) through (0,0,0.333);
// everything beyond it turns rigidly about that axis (geometry, independent of the DH composition).
TEST(DhArmTest, PandaJointTwoSwingsTheArmAboutItsAxis) {
  const DhArm arm(pandaSpec());
  Eigen::VectorXd q = Eigen::VectorXd::Zero(7);
  Poses zero, swung;
  arm.linkPoses(q, zero);
  q[1] = 0.7;
  arm.linkPoses(q, swung);
  // Joint 2 rotates everything beyond it rigidly about its axis (z2 through frame 2's origin).
  const Eigen::Vector3d pivot = zero[1].translation();
  const Eigen::Vector3d axis = zero[1].linear().col(2);
  EXPECT_LT((axis - Eigen::Vector3d(0, 1, 0)).norm(), kTol);  // RotX(-pi/2) z = (0, 1, 0)
  const Eigen::AngleAxisd rotation(0.7, axis);
  for (int i = 2; i < 7; ++i)
    expectNear(swung[i].translation(), pivot + rotation * (zero[i].translation() - pivot), "frame");
  // About +y by 0.7 the upper arm tips towards +x: frame 3 at 0.316 (sin 0.7, 0, cos 0.7) above frame 2.
  expectNear(swung[2].translation(),
             Eigen::Vector3d(0.316 * std::sin(0.7), 0, 0.333 + 0.316 * std::cos(0.7)), "frame 3");
}

// Every joint of both arms, at random configurations and with a turned base: turning joint j by
// delta leaves the frames before it in place and turns frame j and everything beyond it (the flange
// included) rigidly by +delta about joint j's axis, z_j through frame j's origin (modified DH). A
// flipped sense or an axis on the wrong frame breaks this while q = 0 stays right.
TEST(DhArmTest, EveryJointTurnsWhatFollowsItRigidlyAboutItsAxis) {
  for (DhArmSpec spec : {pandaSpec(), crsF3Spec(6)}) {
    spec.base = Eigen::Translation3d(0.1, -0.2, 0.3) * Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, -1, 2).normalized());
    const DhArm arm(spec);
    std::mt19937_64 rng(9);
    for (int trial = 0; trial < 20; ++trial) {
      const Eigen::VectorXd q = randomConfiguration(arm, rng);
      Poses before;
      arm.linkPoses(q, before);
      const Eigen::Isometry3d flange = arm.flangePose(q);
      for (int j = 0; j < arm.dof(); ++j) {
        const double delta = 0.3;
        Eigen::VectorXd turned_q = q;
        turned_q[j] += delta;
        Poses after;
        arm.linkPoses(turned_q, after);
        const Eigen::Vector3d pivot = before[j].translation(), axis = before[j].linear().col(2);
        const Eigen::Matrix3d turn = Eigen::AngleAxisd(delta, axis).toRotationMatrix();
        for (int i = 0; i < j; ++i) expectNear(after[i].translation(), before[i].translation(), "a frame before the joint");
        for (int i = j; i < arm.dof(); ++i) {
          expectNear(after[i].translation(), pivot + turn * (before[i].translation() - pivot), "a frame from the joint on");
          EXPECT_LT((after[i].linear() - turn * before[i].linear()).norm(), kTol) << spec.name << " joint " << j;
        }
        expectNear(arm.flangePose(turned_q).translation(), pivot + turn * (flange.translation() - pivot), "the flange");
      }
    }
  }
}

TEST(DhArmTest, ClosedFormControlPointsMatchTheIsometryChain) {
  // Random configurations, a rotated and shifted base and a tool tip: every control point is a link
  // frame's origin (in chain order) and the last is the tool tip through flangePose.
  for (DhArmSpec spec : {pandaSpec(), crsF3Spec(6)}) {
    spec.base = Eigen::Translation3d(0.1, -0.2, 0.3) * Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized());
    spec.tool_tip = Eigen::Vector3d(0.01, -0.02, 0.12);
    spec.tool = {Shape::box(Eigen::Vector3d(0.08, 0.2, 0.06), Eigen::Isometry3d(Eigen::Translation3d(0, 0.01, 0.05)))};
    const DhArm arm(spec);
    std::mt19937_64 rng(5);
    for (int trial = 0; trial < 50; ++trial) {
      const Eigen::VectorXd q = randomConfiguration(arm, rng);
      Poses poses;
      arm.linkPoses(q, poses);
      Eigen::Matrix3Xd points;
      arm.controlPoints(q, points);
      ASSERT_EQ(points.cols(), arm.numControlPoints());
      const int tip = arm.numControlPoints() - 1 - 2 * static_cast<int>(spec.tool.size());
      size_t frame = 0;
      for (int c = 0; c < tip; ++c) {
        while (frame < poses.size() && (poses[frame].translation() - points.col(c)).norm() > 1e-12) ++frame;
        ASSERT_LT(frame, poses.size()) << spec.name << ": control point " << c << " is no frame origin";
      }
      EXPECT_LT((arm.flangePose(q) * spec.tool_tip - points.col(tip)).norm(), 1e-12) << spec.name;
      for (size_t t = 0; t < spec.tool.size(); ++t) {  // both ends of the box's longest (y) axis
        const Eigen::Vector3d centre = spec.tool[t].pose.translation();
        const double half = 0.5 * spec.tool[t].dims.y();
        EXPECT_LT((arm.flangePose(q) * (centre + Eigen::Vector3d(0, half, 0)) - points.col(tip + 1 + 2 * t)).norm(), 1e-12);
        EXPECT_LT((arm.flangePose(q) * (centre - Eigen::Vector3d(0, half, 0)) - points.col(tip + 2 + 2 * t)).norm(), 1e-12);
      }
    }
  }
}

// mayReach must never rule out a box the robot can touch: at random configurations every link
// shape's own box is reachable, and so is every point of the shapes drawn; a point 5% beyond the
// bound is not, and the bound is not far looser than the farthest point drawn. A point robot
// reaches what meets its bounds grown by its radius.
TEST(RobotTest, MayReachHoldsEveryConfigurationsShapesAndNothingFarBeyond) {
  DhArmSpec panda = pandaSpec();
  panda.base = Eigen::Translation3d(0.1, -0.2, 0.3) * Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized());
  panda.tool = {Shape::box(Eigen::Vector3d(0.08, 0.2, 0.06), Eigen::Isometry3d(Eigen::Translation3d(0, 0.01, 0.05)))};
  const DhArm crs3(crsF3Spec(3)), crs6(crsF3Spec(6)), arm_panda(panda);
  const PlanarArm planar = threeLinkArm();
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(0, 1);
  for (const Robot* robot : std::initializer_list<const Robot*>{&crs3, &crs6, &arm_panda, &planar}) {
    Poses poses;
    robot->linkPoses(robot->lowerLimits(), poses);
    const Eigen::Vector3d origin = poses[0].translation();
    const auto tiny = [](const Eigen::Vector3d& p) { return Eigen::AlignedBox3d(p, p); };
    double farthest = 0;
    for (int trial = 0; trial < 2000; ++trial) {
      const Eigen::VectorXd q = randomConfiguration(*robot, rng);
      robot->linkPoses(q, poses);
      for (int link = 0; link < robot->numLinks(); ++link)
        for (Shape shape : robot->linkShapes(link)) {
          shape.pose = poses[link] * shape.pose;
          const Eigen::AlignedBox3d box = shape.bounds();
          ASSERT_TRUE(robot->mayReach(box)) << robot->name() << " link " << link;
          for (int i = 0; i < 20; ++i) {  // points of the shape, drawn in its box
            const Eigen::Vector3d p = box.min() + box.sizes().cwiseProduct(Eigen::Vector3d(
                                                      unit(rng), unit(rng), unit(rng)));
            if (!shape.contains(p)) continue;
            farthest = std::max(farthest, (p - origin).norm());
            ASSERT_TRUE(robot->mayReach(tiny(p))) << robot->name() << " link " << link << " at " << p.transpose();
          }
        }
    }
    ASSERT_GT(farthest, 0) << robot->name();
    const Eigen::Vector3d out = origin + 1.05 * robot->jointReach()[0] * Eigen::Vector3d(1, 1, 0).normalized();
    EXPECT_FALSE(robot->mayReach(tiny(out))) << robot->name();
    EXPECT_LT(robot->jointReach()[0], 1.25 * farthest) << robot->name() << ": bound far looser than the robot";
  }
  const PointRobot point(vec({0, 0}), vec({1, 2}), 0.1);
  EXPECT_TRUE(point.mayReach(Eigen::AlignedBox3d(Eigen::Vector3d(1.05, 1, -1), Eigen::Vector3d(2, 3, 1))));
  EXPECT_FALSE(point.mayReach(Eigen::AlignedBox3d(Eigen::Vector3d(1.15, 1, -1), Eigen::Vector3d(2, 3, 1))));
  EXPECT_FALSE(point.mayReach(Eigen::AlignedBox3d(Eigen::Vector3d(0, 0, 0.2), Eigen::Vector3d(1, 1, 1))));
}

// configurationAt: a point robot at the point (in 2-D its projection onto z = 0), placed there by
// linkPoses, and nothing outside its limits; an arm has no closed form here.
TEST(RobotTest, ConfigurationAtPlacesAPointRobotAndNoArm) {
  const PointRobot flat(vec({0, 0}), vec({1, 2})), space(vec({0, 0, 0}), vec({1, 2, 3}));
  const auto q = flat.configurationAt(Eigen::Vector3d(0.3, 1.5, 0.7));
  ASSERT_TRUE(q.has_value());
  EXPECT_EQ(*q, vec({0.3, 1.5}));
  const auto r = space.configurationAt(Eigen::Vector3d(0.3, 1.5, 0.7));
  ASSERT_TRUE(r.has_value());
  Poses poses;
  space.linkPoses(*r, poses);
  EXPECT_TRUE(poses[0].translation().isApprox(Eigen::Vector3d(0.3, 1.5, 0.7)));
  EXPECT_FALSE(flat.configurationAt(Eigen::Vector3d(1.1, 1, 0)).has_value());
  EXPECT_FALSE(space.configurationAt(Eigen::Vector3d(0.5, -0.1, 1)).has_value());
  EXPECT_FALSE(DhArm(crsF3Spec(3)).configurationAt(Eigen::Vector3d(0.3, 0.1, 0.4)).has_value());
  EXPECT_FALSE(threeLinkArm().configurationAt(Eigen::Vector3d(0.3, 0.1, 0)).has_value());
}

// stepDisplacement bounds how far any point moves over a motion of that metric length: random
// configurations, random directions scaled to the length under unequal weights, the points of every
// link shape (box corners; a capsule's or sphere's centre plus its radius) before and after.
TEST(RobotTest, StepDisplacementBoundsEveryPointsMotion) {
  const DhArm crs(crsF3Spec(6));
  const PlanarArm planar = threeLinkArm();
  const PointRobot point(vec({0, 0, 0}), vec({1, 2, 3}), 0.01);
  std::mt19937_64 rng(13);
  std::normal_distribution<double> gauss(0, 1);
  for (const Robot* robot : std::initializer_list<const Robot*>{&crs, &planar, &point}) {
    Eigen::VectorXd scale(robot->dof());
    for (int k = 0; k < scale.size(); ++k) scale[k] = 0.5 + 0.25 * k;
    const double length = 0.05, bound = robot->stepDisplacement(scale, length);
    double worst = 0;
    for (int trial = 0; trial < 500; ++trial) {
      Eigen::VectorXd q = 0.5 * (robot->lowerLimits() + robot->upperLimits()), d(robot->dof());
      for (int k = 0; k < q.size(); ++k) q[k] += 0.3 * gauss(rng), d[k] = gauss(rng);
      d *= length / d.cwiseProduct(scale).norm();  // metric length `length`
      Poses before, after;
      robot->linkPoses(q, before);
      robot->linkPoses(q + d, after);
      for (int link = 0; link < robot->numLinks(); ++link)
        for (const Shape& shape : robot->linkShapes(link)) {
          const Eigen::AlignedBox3d box(-0.5 * shape.dims, 0.5 * shape.dims);
          for (int c = 0; c < 8; ++c) {
            const Eigen::Vector3d local =
                shape.kind == ShapeKind::kBox ? box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(c))
                                              : Eigen::Vector3d(c % 2 ? shape.dims.x() : -shape.dims.x(), 0, 0);
            const Eigen::Vector3d p = shape.pose * local;
            worst = std::max(worst, (after[link] * p - before[link] * p).norm());
          }
        }
    }
    EXPECT_LE(worst, bound * (1 + 1e-12)) << robot->name();
    EXPECT_GT(worst, 0.3 * bound) << robot->name() << ": bound far looser than any motion seen";
  }
}

TEST(RobotTest, LimitsAndConfigurationChecks) {
  const PlanarArm arm = threeLinkArm();
  EXPECT_TRUE(arm.withinLimits(vec({kPi, -kPi, 0})));
  EXPECT_FALSE(arm.withinLimits(vec({kPi + 1e-9, 0, 0})));
  EXPECT_FALSE(arm.withinLimits(vec({std::nan(""), 0, 0})));
  EXPECT_THROW(arm.checkConfiguration(vec({0, 0}), "test"), std::invalid_argument);
  EXPECT_THROW(arm.checkConfiguration(vec({0, 0, INFINITY}), "test"), std::invalid_argument);
  EXPECT_NO_THROW(arm.checkConfiguration(vec({0, 0, 0}), "test"));
  EXPECT_THROW(PlanarArm({1.0}, {0.1}, vec({1}), vec({0})), std::invalid_argument);
}

TEST(RobotTest, NonAdjacentPairsSkipLinksWithoutShapes) {
  const PlanarArm arm = threeLinkArm();
  EXPECT_EQ(arm.nonAdjacentLinkPairs(), (std::vector<std::pair<int, int>>{{0, 2}}));
  // CRS-F3: links 4 and 6 (indices 3, 5) have no shapes (zero-length wrist links), so the forearm
  // (index 2) is adjacent to the wrist capsule (index 4).
  const DhArm crs(crsF3Spec(6));
  EXPECT_TRUE(crs.linkShapes(3).empty());
  EXPECT_TRUE(crs.linkShapes(5).empty());
  // The base column (kBase) faces every link with shapes, link 0 (the shoulder offset) included.
  EXPECT_EQ(crs.nonAdjacentLinkPairs(), (std::vector<std::pair<int, int>>{
                                            {Robot::kBase, 0}, {Robot::kBase, 1}, {Robot::kBase, 2},
                                            {Robot::kBase, 4}, {0, 2}, {0, 4}, {1, 4}}));
  EXPECT_TRUE(arm.baseShapes().empty());
}

TEST(RobotTest, DhBaseColumnRunsFromTheBaseToJointOne) {
  // Panda: d1 = 0.333 along the base's z; joint 1's radius. A moved base moves the column with it.
  DhArmSpec spec = pandaSpec();
  spec.base = Eigen::Translation3d(0.5, -0.2, 0.1) * Eigen::AngleAxisd(kPi / 2, Eigen::Vector3d::UnitX());
  const DhArm panda(spec);
  ASSERT_EQ(panda.baseShapes().size(), 1u);
  const Shape& column = panda.baseShapes()[0];
  EXPECT_EQ(column.kind, ShapeKind::kCapsule);
  EXPECT_DOUBLE_EQ(column.dims.x(), 0.06);
  EXPECT_NEAR(column.dims.y(), 0.333, 1e-12);
  // Its axis ends at the base's origin and at joint 1's origin, which no joint angle moves.
  Poses poses;
  panda.linkPoses(Eigen::VectorXd::Constant(7, 0.3), poses);
  const Eigen::Vector3d top = column.pose * Eigen::Vector3d(0, 0, 0.1665);
  const Eigen::Vector3d bottom = column.pose * Eigen::Vector3d(0, 0, -0.1665);
  const bool top_at_joint_1 = (top - poses[0].translation()).norm() < 1e-9;
  EXPECT_NEAR(((top_at_joint_1 ? bottom : top) - spec.base.translation()).norm(), 0, 1e-9);
  EXPECT_NEAR(((top_at_joint_1 ? top : bottom) - poses[0].translation()).norm(), 0, 1e-9);
}

}  // namespace
}  // namespace svmp::robots
