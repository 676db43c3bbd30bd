// IK round trips: every returned solution must put the point on the target (checked through forward
// kinematics), and the configuration a reachable target was generated from must be among them.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "robots/dh_arm.hpp"
#include "robots/planar_arm.hpp"

namespace svmp::robots {
namespace {

constexpr double kPi = std::numbers::pi;

double angleGap(double a, double b) { return std::abs(std::remainder(a - b, 2 * kPi)); }

bool sameAngles(const Eigen::VectorXd& a, const Eigen::VectorXd& b, int first, int last) {
  for (int i = first; i <= last; ++i)
    if (angleGap(a[i], b[i]) > 1e-7) return false;
  return true;
}

Eigen::VectorXd randomAngles(std::mt19937_64& rng, int n) {
  std::uniform_real_distribution<double> angle(-kPi, kPi);
  Eigen::VectorXd q(n);
  for (int i = 0; i < n; ++i) q[i] = angle(rng);
  return q;
}

PlanarArm fiveLinkArm() {
  return PlanarArm({1.0, 0.8, 0.6, 0.5, 0.4}, std::vector<double>(5, 0.05),
                   Eigen::VectorXd::Constant(5, -kPi), Eigen::VectorXd::Constant(5, kPi),
                   Eigen::Vector2d(0.2, 0.1));
}

TEST(PlanarIkTest, RandomReachableTargetsRoundTrip) {
  const PlanarArm arm = fiveLinkArm();
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(0.05, 1.0);
  for (int trial = 0; trial < 300; ++trial) {
    const int link = static_cast<int>(rng() % 5);
    const double s = unit(rng) * arm.lengths()[link];
    const Eigen::VectorXd original = randomAngles(rng, 5);
    const Eigen::Vector2d target = arm.pointOnLink(original, link, s);
    // The seed shares the joints before link-1 (they fix where the two-link problem starts).
    Eigen::VectorXd seed = randomAngles(rng, 5);
    for (int i = 0; i < std::max(0, link - 1); ++i) seed[i] = original[i];
    const auto solutions = arm.solvePointOnLink(link, s, target, seed);
    SCOPED_TRACE(::testing::Message() << "trial " << trial << " link " << link << " s " << s);
    ASSERT_EQ(solutions.size(), link == 0 ? 1u : 2u);  // both elbows (a coincident pair has measure 0)
    bool found_original = false;
    for (const auto& q : solutions) {
      EXPECT_LT((arm.pointOnLink(q, link, s) - target).norm(), 1e-9);
      for (int i = 0; i < 5; ++i) {
        if (i == link || i == link - 1) {
          EXPECT_GT(q[i], -kPi - 1e-12);
          EXPECT_LE(q[i], kPi + 1e-12);
        } else {
          EXPECT_EQ(q[i], seed[i]) << "joint " << i << " must be copied from the seed";
        }
      }
      found_original |= sameAngles(q, original, std::max(0, link - 1), link);
    }
    EXPECT_TRUE(found_original);
    if (link > 0) {
      EXPECT_GT(angleGap(solutions[0][link], solutions[1][link]), 1e-9);
    }
  }
}

TEST(PlanarIkTest, UnreachableTargetsGiveNoSolution) {
  const PlanarArm arm = fiveLinkArm();
  const Eigen::VectorXd seed = Eigen::VectorXd::Zero(5);
  // Link 0: the point at s = 0.5 lies on a circle of radius 0.5 about the base (0.2, 0.1).
  EXPECT_TRUE(arm.solvePointOnLink(0, 0.5, Eigen::Vector2d(0.2, 0.7), seed).empty());
  EXPECT_EQ(arm.solvePointOnLink(0, 0.5, Eigen::Vector2d(0.2, 0.6), seed).size(), 1u);
  // Link 2 with joints 1.. starting at joint 2 = (1.2, 0.1): reach is [0.8 - s, 0.8 + s].
  EXPECT_TRUE(arm.solvePointOnLink(2, 0.3, Eigen::Vector2d(1.2 + 1.2, 0.1), seed).empty());
  EXPECT_TRUE(arm.solvePointOnLink(2, 0.3, Eigen::Vector2d(1.2 + 0.4, 0.1), seed).empty());
  // Fully stretched or fully folded: the two elbows coincide, so exactly one solution.
  const auto stretched = arm.solvePointOnLink(2, 0.3, Eigen::Vector2d(1.2 + 1.1, 0.1), seed);
  ASSERT_EQ(stretched.size(), 1u);
  EXPECT_NEAR(stretched[0][1], 0, 1e-6);
  EXPECT_NEAR(stretched[0][2], 0, 1e-6);
  const auto folded = arm.solvePointOnLink(2, 0.3, Eigen::Vector2d(1.2 + 0.5, 0.1), seed);
  ASSERT_EQ(folded.size(), 1u);
  EXPECT_NEAR(angleGap(folded[0][2], kPi), 0, 1e-6);
  EXPECT_LT((arm.pointOnLink(folded[0], 2, 0.3) - Eigen::Vector2d(1.7, 0.1)).norm(), 1e-9);
}

TEST(PlanarIkTest, RejectsBadArguments) {
  const PlanarArm arm = fiveLinkArm();
  const Eigen::VectorXd seed = Eigen::VectorXd::Zero(5);
  EXPECT_THROW(arm.solvePointOnLink(5, 0.1, Eigen::Vector2d(0, 0), seed), std::invalid_argument);
  EXPECT_THROW(arm.solvePointOnLink(1, 0.0, Eigen::Vector2d(0, 0), seed), std::invalid_argument);
  EXPECT_THROW(arm.solvePointOnLink(1, 0.9, Eigen::Vector2d(0, 0), seed), std::invalid_argument);
  EXPECT_THROW(arm.solvePointOnLink(1, 0.5, Eigen::Vector2d(0, 0), Eigen::VectorXd::Zero(4)),
               std::invalid_argument);
}

void checkDhRoundTrips(const DhArm& arm, int link, std::uint64_t seed_value) {
  std::mt19937_64 rng(seed_value);
  const double length = link == 1 ? 0.1 : link == 2 ? 0.265 : 0.27;
  std::uniform_real_distribution<double> fraction(0.05, 1.0);
  int found = 0;
  constexpr int kTrials = 200;
  for (int trial = 0; trial < kTrials; ++trial) {
    const double s = fraction(rng) * length;
    const Eigen::VectorXd original = randomAngles(rng, arm.dof());
    const Eigen::Vector3d target = arm.pointOnLinkFirstThree(original, link, s);
    const Eigen::VectorXd seed = randomAngles(rng, arm.dof());
    const auto solutions = arm.solvePointOnLinkFirstThree(link, s, target, seed);
    SCOPED_TRACE(::testing::Message() << arm.name() << " link " << link << " trial " << trial);
    ASSERT_FALSE(solutions.empty());
    ASSERT_LE(solutions.size(), 4u);
    bool found_original = false;
    for (const auto& q : solutions) {
      EXPECT_LT((arm.pointOnLinkFirstThree(q, link, s) - target).norm(), 1e-9);
      for (int i = 3; i < arm.dof(); ++i) EXPECT_EQ(q[i], seed[i]);
      found_original |= sameAngles(q, original, 0, link - 1);
    }
    found += found_original;
    if (link == 3) {
      // Shoulder left/right and elbow up/down. Joint 2 sits 0.1 from the base axis, towards the target
      // (horizontal distance rho - 0.1) or away from it (rho + 0.1); each side gives two elbows when the
      // target lies in the annulus [|a2 - s|, a2 + s] about joint 2.
      const double rho = target.head<2>().norm(), h = target.z() - 0.35;
      size_t expected = 0;
      for (double horizontal : {rho - 0.1, rho + 0.1}) {
        const double reach = std::hypot(horizontal, h);
        if (reach > std::abs(0.265 - s) + 1e-9 && reach < 0.265 + s - 1e-9) expected += 2;
      }
      EXPECT_EQ(solutions.size(), expected);
    }
  }
  EXPECT_EQ(found, kTrials);
}

TEST(DhIkTest, CrsF3ThreeJointsRoundTrip) {
  const DhArm arm(crsF3Spec(3));
  for (int link = 1; link <= 3; ++link) checkDhRoundTrips(arm, link, 100 + link);
}

TEST(DhIkTest, CrsF3SixJointsRoundTrip) {
  const DhArm arm(crsF3Spec(6));
  for (int link = 1; link <= 3; ++link) checkDhRoundTrips(arm, link, 200 + link);
}

TEST(DhIkTest, PointOnForearmIsOnTheSegmentElbowToWrist) {
  const DhArm arm(crsF3Spec(6));
  const Eigen::VectorXd q = Eigen::VectorXd::Zero(6);
  // Hand derivation in kinematics_test: elbow (0.1, 0, 0.615), wrist (0.37, 0, 0.615).
  EXPECT_LT((arm.pointOnLinkFirstThree(q, 3, 0.27) - Eigen::Vector3d(0.37, 0, 0.615)).norm(), 1e-12);
  EXPECT_LT((arm.pointOnLinkFirstThree(q, 2, 0.265) - Eigen::Vector3d(0.1, 0, 0.615)).norm(), 1e-12);
  EXPECT_LT((arm.pointOnLinkFirstThree(q, 1, 0.05) - Eigen::Vector3d(0.05, 0, 0.35)).norm(), 1e-12);
}

TEST(DhIkTest, UnreachableAndUnsupported) {
  const DhArm arm(crsF3Spec(6));
  const Eigen::VectorXd seed = Eigen::VectorXd::Zero(6);
  // Far beyond the reach of shoulder + upper arm + forearm.
  EXPECT_TRUE(arm.solvePointOnLinkFirstThree(3, 0.27, Eigen::Vector3d(2, 0, 0.35), seed).empty());
  // Link 1 sweeps a circle of radius s at height 0.35: a point off it has no solution.
  EXPECT_TRUE(arm.solvePointOnLinkFirstThree(1, 0.1, Eigen::Vector3d(0.1, 0, 0.5), seed).empty());
  EXPECT_THROW(arm.solvePointOnLinkFirstThree(4, 0.1, Eigen::Vector3d(0.1, 0, 0.5), seed),
               std::invalid_argument);
  const DhArm panda(pandaSpec());
  EXPECT_THROW(panda.solvePointOnLinkFirstThree(2, 0.1, Eigen::Vector3d(0.1, 0, 0.5),
                                                Eigen::VectorXd::Zero(7)),
               std::logic_error);
}

}  // namespace
}  // namespace svmp::robots
