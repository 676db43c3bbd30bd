// The Fastron proxy checker (cspace/fastron_checker.hpp) against the exact FCL checker on a planar
// 3-link arm with one box: held-out accuracy, every training point classified as labelled after
// training and after an update that follows a move, batched predictions equal to one-by-one checks,
// the exploitation samples spread over the support in collision, parameters with their errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <numbers>
#include <random>

#include "cspace/collision_checker.hpp"
#include "cspace/fastron_checker.hpp"
#include "robots/planar_arm.hpp"
#include "tests/cspace/recording_checker.hpp"

namespace svmp::cspace {
namespace {

constexpr double kPi = std::numbers::pi;

std::shared_ptr<const robots::Robot> arm() {
  return std::make_shared<const robots::PlanarArm>(std::vector<double>{0.4, 0.3, 0.2},
                                                   std::vector<double>{0.04, 0.04, 0.04},
                                                   Eigen::Vector3d::Constant(-kPi), Eigen::Vector3d::Constant(kPi));
}

std::unique_ptr<CollisionChecker> boxAt(const std::shared_ptr<const robots::Robot>& robot, double x, double y) {
  Obstacle o;
  o.name = "box";
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(x, y, 0);
  o.shape = robots::Shape::box(Eigen::Vector3d(0.2, 0.2, 0.2), pose);
  return std::make_unique<CollisionChecker>(robot, std::make_shared<const Environment>(std::vector<Obstacle>{o}), false);
}

// Agreement with the exact checker on n uniform configurations, and the share of colliding ones the
// proxy predicts colliding (TPR) and of free ones it predicts free (TNR).
struct Agreement {
  double accuracy = 0, tpr = 0, tnr = 0, collision_share = 0;
};

Agreement agreement(const FastronChecker& proxy, const ValidityChecker& exact, int n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-kPi, kPi);
  int hits = 0, caught = 0, frees = 0, cleared = 0;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d q(u(rng), u(rng), u(rng));
    const bool free = exact.isValid(q), predicted_free = proxy.isValid(q);
    (free ? frees : hits)++;
    (free ? cleared : caught) += predicted_free == free;
  }
  return {double(caught + cleared) / n, double(caught) / std::max(hits, 1), double(cleared) / std::max(frees, 1),
          double(hits) / n};
}

double accuracy(const FastronChecker& proxy, const ValidityChecker& exact, int n, std::uint64_t seed) {
  return agreement(proxy, exact, n, seed).accuracy;
}

class ProxyFeatures : public ::testing::TestWithParam<FastronFeatures> {};

TEST_P(ProxyFeatures, LearnsTheCSpaceAndFollowsAMove) {
  const auto robot = arm();
  auto exact = boxAt(robot, 0.45, 0.2);
  FastronCheckerOptions o = FastronCheckerOptions::defaults(GetParam());
  o.initial_samples = 3000;
  FastronChecker proxy(robot, o);
  const std::vector<Eigen::VectorXd> extra = {Eigen::Vector3d(0.3, 0.1, -0.2), Eigen::Vector3d(2.5, -1, 0.5)};
  const FastronLearnStats s = proxy.train(*exact, 1, extra);
  ASSERT_TRUE(s.train.converged);
  EXPECT_EQ(s.labelled, 3002);
  // Far better than the constant answer "free", which scores 1 - collision_share (0.88) with TPR 0:
  // seed 11 measured accuracy 0.983 / 0.967 and TPR 0.957 / 0.931 (control points / joints).
  const Agreement a = agreement(proxy, *exact, 3000, 11);
  ASSERT_GT(a.collision_share, 0.05);
  EXPECT_GT(a.accuracy, 0.95);
  EXPECT_GT(a.tpr, 0.85);
  EXPECT_GT(a.tnr, 0.95);
  EXPECT_GT(proxy.supportConfigurations().size(), 10u);
  for (const auto& q : extra) EXPECT_EQ(proxy.isValid(q), exact->isValid(q));
  for (const auto& q : proxy.supportConfigurations()) EXPECT_EQ(proxy.isValid(q), exact->isValid(q));

  exact = boxAt(robot, 0.45, 0.3);  // the box moved 10 cm
  const double stale = accuracy(proxy, *exact, 3000, 12);
  const FastronLearnStats u = proxy.update(*exact, 2, extra);
  EXPECT_TRUE(u.train.converged);
  EXPECT_EQ(u.labelled, static_cast<int>(s.train.support) + o.exploit_samples + o.explore_samples + 2);
  EXPECT_GE(accuracy(proxy, *exact, 3000, 12), stale);
  for (const auto& q : extra) EXPECT_EQ(proxy.isValid(q), exact->isValid(q));
  EXPECT_EQ(&proxy.environment(), &exact->environment());
}

INSTANTIATE_TEST_SUITE_P(Features, ProxyFeatures,
                         ::testing::Values(FastronFeatures::kControlPoints, FastronFeatures::kJoints));

TEST(FastronChecker, BatchEqualsOneByOne) {
  const auto robot = arm();
  const auto exact = boxAt(robot, 0.45, 0.2);
  FastronCheckerOptions o = FastronCheckerOptions::defaults(FastronFeatures::kControlPoints);
  o.initial_samples = 1500;
  FastronChecker proxy(robot, o);
  proxy.train(*exact, 3);
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> u(-kPi, kPi);
  Eigen::MatrixXd qs(3, 100);
  for (int i = 0; i < 100; ++i) qs.col(i) = Eigen::Vector3d(u(rng), u(rng), u(rng));
  qs(0, 7) = 4;  // outside the joint limits
  std::vector<int> batch;
  proxy.checkBatch(qs, batch);
  for (int i = 0; i < 100; ++i) EXPECT_EQ(batch[i], proxy.check(qs.col(i))) << i;
  EXPECT_EQ(batch[7], kJointLimitHit);

}

// With more support points in collision than exploitation samples, each sample perturbs a different
// one drawn at random, not the first ones in storage order (the oldest: the newest, nearest a moved
// obstacle, would never be perturbed).
TEST(FastronChecker, ExploitationPerturbsARandomSubsetOfTheSupportInCollision) {
  const auto robot = arm();
  const auto exact = boxAt(robot, 0.45, 0.2);
  FastronCheckerOptions o = FastronCheckerOptions::defaults(FastronFeatures::kControlPoints);
  o.initial_samples = 1500;
  o.exploit_samples = 5;
  o.exploit_sigma = 1e-9;  // each sample within 1e-8 of the support point it perturbs
  o.explore_samples = 0;
  FastronChecker proxy(robot, o);
  proxy.train(*exact, 3);
  const auto& support = proxy.supportConfigurations();
  std::vector<Eigen::VectorXd> in_collision;  // in storage order
  for (const auto& q : support)
    if (!exact->isValid(q)) in_collision.push_back(q);
  ASSERT_GT(in_collision.size(), 20u);
  test::RecordingChecker recorder(*exact);
  proxy.update(recorder, 4);
  ASSERT_EQ(recorder.asked.size(), support.size() + 5);  // the support relabelled, then the samples
  std::vector<size_t> perturbed;
  for (size_t s = support.size(); s < recorder.asked.size(); ++s) {
    size_t nearest = 0;
    for (size_t i = 1; i < in_collision.size(); ++i)
      if ((in_collision[i] - recorder.asked[s]).norm() < (in_collision[nearest] - recorder.asked[s]).norm()) nearest = i;
    EXPECT_LT((in_collision[nearest] - recorder.asked[s]).norm(), 1e-6);
    perturbed.push_back(nearest);
  }
  std::sort(perturbed.begin(), perturbed.end());
  EXPECT_EQ(std::unique(perturbed.begin(), perturbed.end()), perturbed.end()) << "a support point perturbed twice";
  EXPECT_GT(perturbed.back(), 4u) << "only the first five in storage order were perturbed";
}

TEST(FastronChecker, ParametersAreReadWithTheirBounds) {
  ParameterSet p("test.yaml", "planners.fastron-fk.", {{"gamma", "50"}, {"exploit_samples", "10"}});
  const auto o = FastronCheckerOptions::fromParameters("fastron-fk", p);
  EXPECT_EQ(o.model.gamma, 50);
  EXPECT_EQ(o.exploit_samples, 10);
  EXPECT_EQ(o.features, FastronFeatures::kControlPoints);
  ParameterSet bad("test.yaml", "planners.fastron-rbf.", {{"gamma", "-1"}});
  try {
    FastronCheckerOptions::fromParameters("fastron-rbf", bad);
    FAIL() << "negative gamma accepted";
  } catch (const ScenarioError& e) {
    EXPECT_NE(std::string(e.what()).find("gamma"), std::string::npos) << e.what();
  }
  ParameterSet typo("test.yaml", "planners.fastron-fk.", {{"gama", "5"}});
  FastronCheckerOptions::fromParameters("fastron-fk", typo);
  EXPECT_THROW(typo.requireAllUsed(), ScenarioError);
  EXPECT_THROW(FastronCheckerOptions::fromParameters("fastron-xx", p), ScenarioError);
}

}  // namespace
}  // namespace svmp::cspace
