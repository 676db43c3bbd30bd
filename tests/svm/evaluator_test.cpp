#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <stdexcept>
#include <vector>

#include "svm/model.hpp"
#include "svm/truncated_evaluator.hpp"
#include "tests/svm/ball_problems.hpp"

namespace svmp::svm {
namespace {

// Brute-force sum of the same truncated terms (d^2 < 5/gamma, distance summed in coordinate
// order like nanoflann's L2_Simple_Adaptor so the same terms are kept). scale/grad_scale: sums of
// the absolute terms, the size of the rounding of any summation order.
double bruteTruncated(const BinaryModel& m, const double* q, double* grad, double* scale = nullptr,
                      double* grad_scale = nullptr) {
  double s1 = 0, s2 = 0;
  const double gamma = m.kernel().gamma, r2 = 5.0 / gamma;
  double f = m.bias();
  for (int k = 0; k < m.dim(); ++k) grad[k] = 0;
  for (int s = 0; s < m.numSupportVectors(); ++s) {
    const double* x = m.supportVectors().col(s).data();
    double dist = 0;
    for (int k = 0; k < m.dim(); ++k) {
      const double diff = q[k] - x[k];
      dist += diff * diff;
    }
    if (!(dist < r2)) continue;
    const double term = m.coefficients()[s] * std::exp(-gamma * dist);
    f += term;
    s1 += std::abs(term);
    double largest = 0;
    for (int k = 0; k < m.dim(); ++k) {
      grad[k] += 2 * gamma * term * (x[k] - q[k]);
      largest = std::max(largest, std::abs(x[k] - q[k]));
    }
    s2 += 2 * gamma * std::abs(term) * largest;
  }
  if (scale) *scale = s1;
  if (grad_scale) *grad_scale = s2;
  return f;
}

BinaryModel trainedModel(int d, int n, unsigned long long seed) {
  const auto p = testing::makeBallProblem(d, n, 3, seed);
  const Eigen::VectorXd y = p.binary();
  const Kernel k = Kernel::rbfFromSigma(p.ball_radius / 2);
  const SolverResult r = solveBinary(p.X, y, Eigen::VectorXd::Constant(n, 10.0), k, {});
  return BinaryModel::fromSolution(p.X, y, r, k);
}

TEST(TruncatedRbfEvaluator, MatchesBruteForceAndBoundsTheFullSum) {
  for (int d : {2, 6}) {
    const BinaryModel m = trainedModel(d, 4000, 50 + d);
    const TruncatedRbfEvaluator ev(m);
    EXPECT_NEAR(ev.truncationBound(), m.coefficients().cwiseAbs().sum() * std::exp(-5.0), 1e-12);
    const auto p = testing::makeBallProblem(d, 4000, 3, 50 + d);
    const Eigen::MatrixXd Q = testing::nearQueries(p.X, 2000, p.ball_radius / 4, 3);
    const double scale = m.coefficients().cwiseAbs().sum();
    double worst_full = 0;
    for (int s = 0; s < Q.cols(); ++s) {
      std::vector<double> g(d), gb(d), gf(d);
      const double f = ev.decisionAndGradient(Q.col(s).data(), g.data());
      double fscale = 0, gscale = 0;
      const double fb = bruteTruncated(m, Q.col(s).data(), gb.data(), &fscale, &gscale);
      EXPECT_NEAR(f, ev.decision(Q.col(s).data()), 1e-12 * scale);
      // 1e-12 relative to the summed magnitudes: the two sums add the same terms in other orders.
      EXPECT_NEAR(f, fb, 1e-12 * std::max(1.0, fscale));
      for (int k = 0; k < d; ++k) EXPECT_NEAR(g[k], gb[k], 1e-12 * std::max(1.0, gscale));
      const double full = m.decisionAndGradient(Q.col(s).data(), gf.data());
      worst_full = std::max(worst_full, std::abs(full - f));
    }
    EXPECT_LE(worst_full, ev.truncationBound());
  }
}

// The exact variants are the full sum (the risk descent's polish, SVPP): the same values and
// gradients as the model's scalar loop, near the data and far from it, where the truncated F keeps
// nothing.
TEST(TruncatedRbfEvaluator, ExactVariantsAreTheFullSum) {
  EXPECT_LT(std::exp(-TruncatedRbfEvaluator::kExactCutoff), 1e-16);
  for (int d : {2, 6}) {
    const BinaryModel m = trainedModel(d, 2000, 70 + d);
    const TruncatedRbfEvaluator ev(m);
    const auto p = testing::makeBallProblem(d, 2000, 3, 70 + d);
    Eigen::MatrixXd Q = testing::nearQueries(p.X, 400, p.ball_radius / 4, 5);
    Q.rightCols(100) *= 1.5;  // some beyond the data
    const double scale = m.coefficients().cwiseAbs().sum();
    int differs = 0;
    for (int s = 0; s < Q.cols(); ++s) {
      std::vector<double> g(d), gf(d), gt(d);
      const double f = ev.exactDecisionAndGradient(Q.col(s).data(), g.data());
      const double full = m.decisionAndGradient(Q.col(s).data(), gf.data());
      EXPECT_NEAR(f, full, 1e-13 * scale);
      EXPECT_NEAR(ev.exactDecision(Q.col(s).data()), full, 1e-13 * scale);
      // Each gradient term is at most |coef| sqrt(2 gamma / e).
      for (int k = 0; k < d; ++k) EXPECT_NEAR(g[k], gf[k], 1e-13 * scale * std::sqrt(2 * m.kernel().gamma));
      differs += std::abs(ev.decisionAndGradient(Q.col(s).data(), gt.data()) - full) > 1e-9 * scale;
    }
    EXPECT_GT(differs, 0);  // the truncated F leaves terms out that the exact sum keeps
  }
}

// d > 16 takes the nanoflann radius-search path.
TEST(TruncatedRbfEvaluator, HighDimensionMatchesBruteForce) {
  const int d = 18, m = 3000;
  std::mt19937_64 rng(12);
  std::uniform_real_distribution<double> uni(0, 1);
  Eigen::MatrixXd sv(d, m);
  Eigen::VectorXd coef(m);
  for (int s = 0; s < m; ++s) {
    for (int k = 0; k < d; ++k) sv(k, s) = uni(rng);
    coef[s] = 10 * (uni(rng) - 0.5);
  }
  const BinaryModel model(sv, coef, 0.3, Kernel::rbf(8.0));  // radius^2 = 0.625
  const TruncatedRbfEvaluator ev(model);
  int nonzero = 0;
  for (int s = 0; s < 200; ++s) {
    std::vector<double> g(d), gb(d);
    double fscale = 0, gscale = 0;
    const double* q = sv.col(s).data();
    const double f = ev.decisionAndGradient(q, g.data());
    const double fb = bruteTruncated(model, q, gb.data(), &fscale, &gscale);
    nonzero += fscale > 0;
    EXPECT_NEAR(f, fb, 1e-12 * std::max(1.0, fscale));
    for (int k = 0; k < d; ++k) EXPECT_NEAR(g[k], gb[k], 1e-12 * std::max(1.0, gscale));
  }
  EXPECT_EQ(nonzero, 200);
}

TEST(TruncatedRbfEvaluator, ConstEvaluationIsThreadSafe) {
  const BinaryModel m = trainedModel(6, 3000, 61);
  const TruncatedRbfEvaluator ev(m);
  const auto p = testing::makeBallProblem(6, 3000, 3, 61);
  const Eigen::MatrixXd Q = testing::nearQueries(p.X, 4000, 0.05, 9);
  std::vector<double> serial(Q.cols()), parallel(Q.cols());
  for (int s = 0; s < Q.cols(); ++s) {
    double g[6];
    serial[s] = ev.decisionAndGradient(Q.col(s).data(), g) + g[0];
  }
#pragma omp parallel for num_threads(2)
  for (int s = 0; s < Q.cols(); ++s) {
    double g[6];
    parallel[s] = ev.decisionAndGradient(Q.col(s).data(), g) + g[0];
  }
  EXPECT_EQ(serial, parallel);
}

TEST(TruncatedRbfEvaluator, SurvivesTheModelAndMoves) {
  std::unique_ptr<TruncatedRbfEvaluator> ev;
  Eigen::VectorXd q;
  double expected;
  {
    const BinaryModel m = trainedModel(2, 1000, 70);
    q = m.supportVectors().col(0);  // near a support vector F is not just the bias
    ev = std::make_unique<TruncatedRbfEvaluator>(m);
    expected = ev->decision(q.data());
    ASSERT_GT(std::abs(expected - m.bias()), 1e-3);
  }
  TruncatedRbfEvaluator moved = std::move(*ev);
  ev.reset();
  EXPECT_EQ(moved.decision(q.data()), expected);
}

TEST(TruncatedRbfEvaluator, RejectsNonRbfKernels) {
  Kernel lin;
  lin.type = KernelType::kLinear;
  const BinaryModel m(Eigen::MatrixXd::Ones(2, 3), Eigen::VectorXd::Ones(3), 0.0, lin);
  try {
    TruncatedRbfEvaluator ev(m);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("RBF"), std::string::npos);
  }
  const BinaryModel b(Eigen::MatrixXd::Ones(2, 3), Eigen::VectorXd::Ones(3), 0.0,
                      Kernel::blockSum(Kernel::rbfFromSigma(1), 1));
  EXPECT_THROW(TruncatedRbfEvaluator{b}, std::invalid_argument);
}

}  // namespace
}  // namespace svmp::svm
