// Risk function: gradient against finite differences under a non-unit metric, and the descent to the
// decision boundary between two parallel walls (whose boundary is the corridor's midline).
#include <gtest/gtest.h>

#include <random>

#include "planners/risk_function.hpp"
#include "robots/planar_arm.hpp"
#include "planners/svmp_planner.hpp"
#include "test_world.hpp"

namespace svmp::planners {
namespace {

using test::makeWorld;

// Random RBF model in scaled coordinates x (dim 3): F(x) = sum coef_i exp(-gamma |x - sv_i|^2) + b.
svm::BinaryModel randomModel(std::mt19937_64& rng, int dim, int n, double sigma) {
  std::uniform_real_distribution<double> unit(-1, 1);
  Eigen::MatrixXd sv(dim, n);
  Eigen::VectorXd coef(n);
  for (int i = 0; i < n; ++i) {
    for (int d = 0; d < dim; ++d) sv(d, i) = unit(rng);
    coef[i] = 2 * unit(rng);
  }
  return svm::BinaryModel(sv, coef, 0.3 * unit(rng), svm::Kernel::rbfFromSigma(sigma));
}

TEST(RiskFunction, EvaluatesTheModelOnScaledCoordinates) {
  std::mt19937_64 rng(11);
  const Eigen::Vector3d weights(4.0, 0.25, 9.0);
  const Eigen::Vector3d scale = weights.cwiseSqrt();
  const svm::BinaryModel model = randomModel(rng, 3, 40, 0.6);
  const RiskFunction risk({model}, {7}, scale, /*truncated=*/false);
  EXPECT_EQ(risk.classIndex(7), 0);
  EXPECT_EQ(risk.classIndex(3), -1);
  std::uniform_real_distribution<double> unit(-0.6, 0.6);
  for (int t = 0; t < 20; ++t) {
    const Eigen::Vector3d q(unit(rng), unit(rng), unit(rng));
    const Eigen::Vector3d x = q.cwiseProduct(scale);
    EXPECT_NEAR(risk.decision(0, q), model.decision(x.data()), 1e-12);
    EXPECT_NEAR(risk.risk(0, q), std::abs(model.decision(x.data())), 1e-12);
  }
}

void checkGradient(bool truncated, double tolerance) {
  std::mt19937_64 rng(12);
  const Eigen::Vector3d weights(4.0, 0.25, 9.0);
  const RiskFunction risk({randomModel(rng, 3, 60, 0.7), randomModel(rng, 3, 60, 0.7)}, {1, 2},
                          weights.cwiseSqrt(), truncated);
  std::uniform_real_distribution<double> unit(-0.5, 0.5);
  const double h = 1e-6;
  for (int k = 0; k < 2; ++k)
    for (int t = 0; t < 25; ++t) {
      const Eigen::Vector3d q(unit(rng), unit(rng), unit(rng));
      Eigen::VectorXd grad(3);
      const double f = risk.decisionAndGradient(k, q, grad);
      EXPECT_NEAR(f, risk.decision(k, q), 1e-12);
      for (int d = 0; d < 3; ++d) {
        Eigen::Vector3d plus = q, minus = q;
        plus[d] += h;
        minus[d] -= h;
        const double fd = (risk.decision(k, plus) - risk.decision(k, minus)) / (2 * h);
        EXPECT_NEAR(grad[d], fd, tolerance * std::max(1.0, std::abs(fd)))
            << "class " << k << " dim " << d << " at " << q.transpose();
      }
    }
}

TEST(RiskFunction, GradientMatchesFiniteDifferencesWithWeightedMetric) { checkGradient(false, 1e-6); }

TEST(RiskFunction, TruncatedGradientMatchesFiniteDifferencesWithWeightedMetric) {
  checkGradient(true, 1e-5);
}

// Two parallel walls (separate obstacles) y < 0.4 and y > 0.6 across the unit square: the boundary
// between their classes is the midline y = 0.5 by symmetry. `weights` change the metric (and so the
// trees and the kernel) without breaking the symmetry.
std::string corridor(const std::string& weights) {
  return "robot: {type: point, bounds: {lower: [0, 0], upper: [1, 1]}}\n"
         "obstacles:\n"
         "  - {name: below, shape: box, size: [1.4, 0.5, 1.0], position: [0.5, 0.15, 0]}\n"
         "  - {name: above, shape: box, size: [1.4, 0.5, 1.0], position: [0.5, 0.85, 0]}\n"
         "start: [0.05, 0.5]\n"
         "goal: [0.95, 0.5]\n"
         "resolution: 0.01\n"
         "metric_weights: " + weights + "\n";
}

void checkDescentToMidline(const std::string& weights, double sigma, double step) {
  auto w = makeWorld(corridor(weights));
  SvmpOptions options;
  options.sigma = sigma;
  options.step = step;
  options.samples_per_tree = 300;
  SvmpPlanner svmp(w->context, options);
  PhaseTimes times;
  svmp.sampleObstacle(5, times);
  svmp.trainMultiSvm(times);
  const RiskFunction* risk = svmp.risk();
  ASSERT_NE(risk, nullptr);
  ASSERT_EQ(risk->numClasses(), 2);
  DescentOptions descent;
  descent.max_step = sigma;
  for (const char* wall : {"below", "above"}) {
    const int k = risk->classIndex(wall == std::string("below") ? 1 : 2);
    ASSERT_GE(k, 0);
    for (double x : {0.2, 0.35, 0.5, 0.65, 0.8})
      for (double y : {0.41, 0.43, 0.57, 0.59}) {
        const Eigen::Vector2d q0(x, y);
        const DescentResult r = risk->descend(k, q0, w->space, descent);
        SCOPED_TRACE(testing::Message() << "wall " << wall << " from " << q0.transpose() << " weights "
                                        << weights << ": reached " << r.q.transpose() << " risk " << r.risk
                                        << " after " << r.iterations << " iterations");
        EXPECT_EQ(r.status, DescentStatus::kOnBoundary) << descentStatusName(r.status);
        EXPECT_LE(r.risk, descent.tolerance);
        const Eigen::Vector2d scaled = r.q.cwiseProduct(risk->scale());
        const double exact = std::abs(risk->model(k).decision(scaled.data()));
        EXPECT_NEAR(r.risk, r.exact ? exact : risk->risk(k, r.q), 1e-12);
        EXPECT_NEAR(r.q.y(), 0.5, 0.03);
        EXPECT_TRUE(w->space.contains(r.q));
        // The descent moves towards the boundary, not along it: x barely changes (in the weighted
        // metric, where the descent is steepest).
        EXPECT_NEAR(scaled.x(), x * risk->scale().x(), 0.05);
      }
  }
}

TEST(RiskFunction, DescentFromEitherWallEndsOnTheMidline) { checkDescentToMidline("[1, 1]", 0.1, 0.05); }

TEST(RiskFunction, DescentEndsOnTheMidlineWithWeightedMetric) {
  // Weighted distance: y counts twice as much as x (w_y = 4), so sigma and step are in scaled units.
  checkDescentToMidline("[0.5, 4]", 0.2, 0.1);
}

TEST(RiskFunction, DescentStaysInsideTheBounds) {
  std::mt19937_64 rng(13);
  // A model whose boundary lies outside the space: the descent must stop at the bounds.
  Eigen::MatrixXd sv(2, 1);
  sv << 3.0, 3.0;
  Eigen::VectorXd coef(1);
  coef << 1.0;
  const RiskFunction risk({svm::BinaryModel(sv, coef, -0.5, svm::Kernel::rbfFromSigma(1.0))}, {1},
                          Eigen::Vector2d::Ones(), false);
  const cspace::ConfigurationSpace space(Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 1), Eigen::Vector2d(1, 1));
  DescentOptions options;
  const DescentResult r = risk.descend(0, Eigen::Vector2d(0.2, 0.3), space, options);
  EXPECT_TRUE(space.contains(r.q)) << r.q.transpose();
  EXPECT_NE(r.status, DescentStatus::kOnBoundary);
}

// The FK kernel (Das & Yip 2019, eq. 4) as SVMP's: models on a planar arm's control points, F equal to
// the block-sum RBF on the control points it was trained with, dF/dq by the chain rule through the
// control points against central differences, and a descent that ends on F = 0.
TEST(RiskFunction, ForwardKinematicsKernelOnControlPoints) {
  const robots::PlanarArm arm({1.0, 0.8, 0.5}, {0.1, 0.1, 0.1}, Eigen::Vector3d::Constant(-3.1),
                              Eigen::Vector3d::Constant(3.1));
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> u(-3, 3);
  Eigen::MatrixXd q(3, 300);
  std::vector<int> labels(300);
  Eigen::Matrix3Xd points;
  for (int i = 0; i < 300; ++i) {
    q.col(i) = Eigen::Vector3d(u(rng), u(rng), u(rng));
    arm.controlPoints(q.col(i), points);
    labels[i] = points(0, 2) > 0.5 ? 1 : 2;  // tip right or left of x = 0.5
  }
  const Eigen::Vector3d scale(1, 2, 0.5);
  const RiskFunction risk = RiskFunction::trainOneVsRest(q, labels, 0.3, 100, {{1, 1.0}, {2, 1.0}}, {}, scale,
                                                         true, 1, &arm);
  ASSERT_EQ(risk.model(0).dim(), 3 * arm.numControlPoints());
  EXPECT_FALSE(risk.model(0).kernel().isPlainRbf());
  int descended = 0;
  for (int t = 0; t < 20; ++t) {
    const Eigen::Vector3d at(u(rng), u(rng), u(rng));
    arm.controlPoints(at, points);
    const Eigen::VectorXd phi = Eigen::Map<const Eigen::VectorXd>(points.data(), points.size());
    EXPECT_NEAR(risk.decision(0, at), risk.model(0).decision(phi.data()), 1e-12);
    Eigen::VectorXd grad(3);
    risk.decisionAndGradient(0, at, grad);
    for (int d = 0; d < 3; ++d) {
      Eigen::Vector3d plus = at, minus = at;
      plus[d] += 1e-5;
      minus[d] -= 1e-5;
      const double fd = (risk.decision(0, plus) - risk.decision(0, minus)) / 2e-5;
      EXPECT_NEAR(grad[d], fd, 1e-4 * std::max(1.0, std::abs(fd))) << "dim " << d << " at " << at.transpose();
    }
    const cspace::ConfigurationSpace space(arm.lowerLimits(), arm.upperLimits(), scale.cwiseAbs2());
    const DescentResult r = risk.descend(0, at, space, DescentOptions{});
    EXPECT_LE(std::abs(risk.decision(0, r.q)), std::abs(risk.decision(0, at)) + 1e-12);
    if (r.status == DescentStatus::kOnBoundary) {
      ++descended;
      EXPECT_LE(std::abs(risk.decision(0, r.q)), 1e-3);
    }
  }
  EXPECT_GE(descended, 10);  // the rest start where F is flat (far from every support vector)
}

}  // namespace
}  // namespace svmp::planners
