#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

#include "svm/smo_solver.hpp"
#include "svm/warm_start.hpp"
#include "tests/svm/ball_problems.hpp"
#include "tests/svm/test_helpers.hpp"

namespace svmp::svm {
namespace {

using testing::makeBallProblem;

struct Edited {
  Eigen::MatrixXd X;
  Eigen::VectorXd y;
  std::vector<Eigen::Index> previous_index;
};

// Moves, removes and adds `fraction` of the samples (moves by a tenth of a ball radius).
Edited edit(const testing::BallProblem& p, unsigned long long problem_seed,
            const Eigen::VectorXd& y, double fraction, unsigned long long seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uni(0, 1);
  std::normal_distribution<double> normal(0, 1);
  const Eigen::Index n = p.X.cols(), d = p.X.rows();
  // Same problem seed, more samples: new samples from the same balls.
  const auto more = makeBallProblem(static_cast<int>(d), static_cast<int>(2 * n), 3, problem_seed);
  Edited e;
  std::vector<Eigen::VectorXd> cols;
  std::vector<double> labels;
  for (Eigen::Index i = 0; i < n; ++i) {
    const double u = uni(rng);
    if (u < fraction) continue;  // removed
    Eigen::VectorXd x = p.X.col(i);
    if (u < 2 * fraction) {
      Eigen::VectorXd step(d);
      for (Eigen::Index k = 0; k < d; ++k) step[k] = normal(rng);
      x += 0.1 * p.ball_radius * step.normalized();
    }
    cols.push_back(x);
    labels.push_back(y[i]);
    e.previous_index.push_back(i);
  }
  for (Eigen::Index i = 0; i < static_cast<Eigen::Index>(fraction * n); ++i) {
    cols.push_back(more.X.col(n + i));
    labels.push_back(more.labels[n + i] == 1 ? 1.0 : -1.0);
    e.previous_index.push_back(-1);
  }
  // Shuffle so kept samples change position too.
  std::vector<size_t> order(cols.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::shuffle(order.begin(), order.end(), rng);
  e.X.resize(d, static_cast<Eigen::Index>(cols.size()));
  e.y.resize(static_cast<Eigen::Index>(cols.size()));
  std::vector<Eigen::Index> prev(cols.size());
  for (size_t s = 0; s < order.size(); ++s) {
    e.X.col(s) = cols[order[s]];
    e.y[s] = labels[order[s]];
    prev[s] = e.previous_index[order[s]];
  }
  e.previous_index = prev;
  return e;
}

TEST(WarmStart, ReachesTheColdObjective) {
  for (int d : {2, 6}) {
    const auto p = makeBallProblem(d, 4000, 3, 40 + d);
    const Eigen::VectorXd y = p.binary();
    const Kernel k = Kernel::rbfFromSigma(p.ball_radius / 2);
    SolverOptions opt;
    const Eigen::VectorXd C = Eigen::VectorXd::Constant(y.size(), 10.0);
    const SolverResult first = solveBinary(p.X, y, C, k, opt);
    const Edited e = edit(p, 40 + d, y, 0.05, 99 + d);
    const Eigen::VectorXd C2 = Eigen::VectorXd::Constant(e.y.size(), 10.0);
    const WarmStart warm = makeWarmStart(p.X, y, C, first, e.previous_index);
    SolverOptions tight = opt;
    tight.eps = 1e-5;  // both well inside 1e-6 relative of the true optimum
    const SolverResult cold = solveBinary(e.X, e.y, C2, k, tight);
    const SolverResult hot = solveBinary(e.X, e.y, C2, k, tight, &warm);
    ASSERT_EQ(hot.status, SolverStatus::kOptimal);
    EXPECT_NEAR(hot.objective, cold.objective, 1e-6 * std::abs(cold.objective)) << "d=" << d;
    EXPECT_GT(hot.warm.moved, 0);
    EXPECT_GT(hot.warm.added, 0);
    EXPECT_GT(hot.warm.removed, 0);
    EXPECT_NEAR(e.y.dot(hot.alpha), 0.0, 1e-9);
    // Default eps too: the warm result satisfies KKT exactly like a cold one.
    const SolverResult hot3 = solveBinary(e.X, e.y, C2, k, opt, &warm);
    const SolverResult cold3 = solveBinary(e.X, e.y, C2, k, opt);
    EXPECT_LT(hot3.iterations, cold3.iterations);  // at eps = 1e-5 the final phase dominates both
    const Eigen::VectorXd G = testing::exactGradient(e.X, e.y, hot3.alpha, k);
    EXPECT_LT(testing::kktViolation(e.y, C2, hot3.alpha, G), opt.eps);
  }
}

TEST(WarmStart, InitialGradientIsExact) {
  const auto p = makeBallProblem(3, 1500, 3, 8);
  const Eigen::VectorXd y = p.binary();
  const Kernel k = Kernel::rbfFromSigma(p.ball_radius / 2);
  const Eigen::VectorXd C = Eigen::VectorXd::Constant(y.size(), 10.0);
  const SolverResult first = solveBinary(p.X, y, C, k, {});
  const Edited e = edit(p, 8, y, 0.05, 5);
  // New C (lower for some samples): clipping changes multipliers of kept samples too.
  Eigen::VectorXd C2 = Eigen::VectorXd::Constant(e.y.size(), 10.0);
  for (Eigen::Index i = 0; i < C2.size(); i += 7) C2[i] = 4.0;
  const WarmStart warm = makeWarmStart(p.X, y, C, first, e.previous_index);
  ASSERT_EQ(warm.validate(e.X.cols(), e.X.rows()), "");
  KernelColumns data(e.X, k);
  Eigen::VectorXd alpha, G, G_bar;
  const WarmStartCounts counts =
      detail::initialiseFromWarmStart(warm, e.X, e.y, C2, data, alpha, G, G_bar);
  EXPECT_NEAR(e.y.dot(alpha), 0.0, 1e-9);
  EXPECT_GE(alpha.minCoeff(), 0.0);
  EXPECT_LE((alpha - C2).maxCoeff(), 0.0);
  EXPECT_GT(counts.adjusted, 0);
  EXPECT_LT(counts.columns, e.X.cols() / 2);
  const Eigen::VectorXd G_exact = testing::exactGradient(e.X, e.y, alpha, k);
  EXPECT_LT((G - G_exact).cwiseAbs().maxCoeff(), 1e-4);  // previous G came from float columns
  Eigen::VectorXd at_bound = Eigen::VectorXd::Zero(alpha.size());
  for (Eigen::Index i = 0; i < alpha.size(); ++i) at_bound[i] = alpha[i] >= C2[i] ? C2[i] : 0.0;
  const Eigen::VectorXd Gb_exact =
      testing::exactGradient(e.X, e.y, at_bound, k) + Eigen::VectorXd::Ones(alpha.size());
  EXPECT_LT((G_bar - Gb_exact).cwiseAbs().maxCoeff(), 1e-4);
}

TEST(WarmStart, UnchangedProblemNeedsNoIterations) {
  const auto p = makeBallProblem(2, 2000, 3, 4);
  const Eigen::VectorXd y = p.binary();
  const Eigen::VectorXd C = Eigen::VectorXd::Constant(y.size(), 10.0);
  const Kernel k = Kernel::rbfFromSigma(0.1);
  const SolverResult first = solveBinary(p.X, y, C, k, {});
  std::vector<Eigen::Index> same(2000);
  for (int i = 0; i < 2000; ++i) same[i] = i;
  const WarmStart warm = makeWarmStart(p.X, y, C, first, same);
  const SolverResult again = solveBinary(p.X, y, C, k, {}, &warm);
  EXPECT_EQ(again.iterations, 0);
  EXPECT_EQ(again.warm.columns, 0);
  EXPECT_NEAR(again.objective, first.objective, 1e-12 * std::abs(first.objective));
}

TEST(WarmStart, InconsistentWarmStartThrows) {
  const auto p = makeBallProblem(2, 100, 2, 4);
  const Eigen::VectorXd y = p.binary();
  const Eigen::VectorXd C = Eigen::VectorXd::Constant(100, 1.0);
  const Kernel k = Kernel::rbfFromSigma(0.1);
  const SolverResult first = solveBinary(p.X, y, C, k, {});
  std::vector<Eigen::Index> bad(100, 0);  // sample 0 continued 100 times
  const WarmStart w1 = makeWarmStart(p.X, y, C, first, bad);
  try {
    solveBinary(p.X, y, C, k, {}, &w1);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("continued twice"), std::string::npos);
  }
  const WarmStart w2 = makeWarmStart(p.X, y, C, first, std::vector<Eigen::Index>(50, -1));
  EXPECT_THROW(solveBinary(p.X, y, C, k, {}, &w2), std::invalid_argument);
}

}  // namespace
}  // namespace svmp::svm
