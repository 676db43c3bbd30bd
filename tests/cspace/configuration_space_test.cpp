// ConfigurationSpace: the weighted metric of thesis eq. 4.3, interpolation, steering and sampling.
#include <gtest/gtest.h>

#include <cmath>

#include "cspace/configuration_space.hpp"

namespace svmp::cspace {
namespace {

ConfigurationSpace weightedSpace() {
  return ConfigurationSpace(Eigen::Vector3d(-1, -2, 0), Eigen::Vector3d(1, 2, 10), Eigen::Vector3d(4, 1, 0.25));
}

TEST(ConfigurationSpaceTest, WeightedMetricByHand) {
  const ConfigurationSpace space = weightedSpace();
  // sqrt(4 * 1^2 + 1 * 2^2 + 0.25 * 4^2) = sqrt(4 + 4 + 4) = sqrt(12).
  EXPECT_NEAR(space.distance(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 2, 4)), std::sqrt(12.0), 1e-12);
  EXPECT_NEAR(space.distance(Eigen::Vector3d(1, 2, 4), Eigen::Vector3d(0, 0, 0)), std::sqrt(12.0), 1e-12);
  EXPECT_EQ(space.distance(Eigen::Vector3d(0.3, 1, 2), Eigen::Vector3d(0.3, 1, 2)), 0.0);
  EXPECT_NEAR(space.metricScale()[0], 2.0, 1e-15);
  EXPECT_NEAR(space.metricScale()[2], 0.5, 1e-15);
}

TEST(ConfigurationSpaceTest, InterpolationHitsEndpointsAndMidpoint) {
  const ConfigurationSpace space = weightedSpace();
  const Eigen::Vector3d a(-1, 2, 0), b(1, -2, 8);
  Eigen::VectorXd out(3);
  space.interpolate(a, b, 0, out);
  EXPECT_EQ(out, Eigen::VectorXd(a));
  space.interpolate(a, b, 1, out);
  EXPECT_LT((out - b).norm(), 1e-15);
  space.interpolate(a, b, 0.5, out);
  EXPECT_LT((out - Eigen::Vector3d(0, 0, 4)).norm(), 1e-15);
}

TEST(ConfigurationSpaceTest, SteerTakesOneStepOfMetricLength) {
  const ConfigurationSpace space = weightedSpace();
  const Eigen::VectorXd from = Eigen::Vector3d(0, 0, 0), to = Eigen::Vector3d(1, 2, 4);  // length sqrt(12)
  const Eigen::VectorXd stepped = space.steer(from, to, 1.0);
  EXPECT_NEAR(space.distance(from, stepped), 1.0, 1e-12);
  EXPECT_LT((stepped - to / std::sqrt(12.0)).norm(), 1e-12);  // along the segment
  EXPECT_EQ(space.steer(from, to, 10.0), Eigen::VectorXd(to));
}

TEST(ConfigurationSpaceTest, SamplingStaysInsideAndFollowsTheSeed) {
  const ConfigurationSpace space = weightedSpace();
  Rng rng(42), same(42), other(43);
  Eigen::VectorXd low = Eigen::VectorXd::Constant(3, 1e9), high = Eigen::VectorXd::Constant(3, -1e9);
  for (int i = 0; i < 2000; ++i) {
    const Eigen::VectorXd q = space.sampleUniform(rng);
    ASSERT_TRUE(space.contains(q)) << q.transpose();
    EXPECT_EQ(q, space.sampleUniform(same));
    low = low.cwiseMin(q);
    high = high.cwiseMax(q);
  }
  // 2000 uniform samples come within 1% of every bound.
  EXPECT_LT(((low - space.lower()).array() / (space.upper() - space.lower()).array()).maxCoeff(), 0.01);
  EXPECT_LT(((space.upper() - high).array() / (space.upper() - space.lower()).array()).maxCoeff(), 0.01);
  Rng fresh(42);
  EXPECT_NE(space.sampleUniform(fresh), space.sampleUniform(other));
}

TEST(ConfigurationSpaceTest, ContainsAndClamp) {
  const ConfigurationSpace space = weightedSpace();
  EXPECT_TRUE(space.contains(Eigen::Vector3d(1, -2, 10)));
  EXPECT_FALSE(space.contains(Eigen::Vector3d(1.001, 0, 5)));
  EXPECT_FALSE(space.contains(Eigen::Vector2d(0, 0)));
  Eigen::VectorXd q = Eigen::Vector3d(5, -5, 5);
  space.clamp(q);
  EXPECT_EQ(q, Eigen::VectorXd(Eigen::Vector3d(1, -2, 5)));
}

TEST(ConfigurationSpaceTest, ConstructorRejectsBadInput) {
  const Eigen::Vector2d lo(0, 0), hi(1, 1), w(1, 1);
  EXPECT_THROW(ConfigurationSpace(lo, hi, Eigen::Vector3d(1, 1, 1)), std::invalid_argument);
  EXPECT_THROW(ConfigurationSpace(Eigen::VectorXd(), Eigen::VectorXd(), Eigen::VectorXd()),
               std::invalid_argument);
  EXPECT_THROW(ConfigurationSpace(hi, lo, w), std::invalid_argument);
  EXPECT_THROW(ConfigurationSpace(lo, Eigen::Vector2d(1, INFINITY), w), std::invalid_argument);
  EXPECT_THROW(ConfigurationSpace(lo, hi, Eigen::Vector2d(1, 0)), std::invalid_argument);
  EXPECT_THROW(ConfigurationSpace(lo, hi, Eigen::Vector2d(1, NAN)), std::invalid_argument);
  try {
    ConfigurationSpace(lo, hi, Eigen::Vector2d(1, -3));
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("weight 2"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace svmp::cspace
