#include <numeric>
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
    const WarmStart warm = makeWarmStart(p.X, y, C, k, first, e.previous_index);
    SolverOptions tight = opt;
    tight.eps = 1e-5;  // both well inside 1e-6 relative of the true optimum
    const SolverResult cold = solveBinary(e.X, e.y, C2, k, tight);
    const SolverResult hot = solveBinary(e.X, e.y, C2, k, tight, &warm);
    ASSERT_EQ(hot.status, SolverStatus::kOptimal);
    EXPECT_NEAR(hot.objective, cold.objective, 1e-6 * std::abs(cold.objective)) << "d=" << d;
    // The RBF dual is strictly convex: the same solution, not only the same objective (alphas,
    // bias, decisions on the training set).
    EXPECT_LT((hot.alpha - cold.alpha).cwiseAbs().maxCoeff(), 1e-2 * 10.0) << "d=" << d;  // 1% of C; measured 0.3%
    EXPECT_NEAR(hot.bias, cold.bias, 1e-4) << "d=" << d;  // measured 2.4e-6 and 1.3e-7
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

// Keeps every sample but those with index % drop == 0 (drop 0: none), then adds `added` new ones.
Edited removeAndAdd(const testing::BallProblem& p, const Eigen::VectorXd& y, int drop, int added,
                    unsigned long long problem_seed) {
  const Eigen::Index n = p.X.cols();
  const auto more = makeBallProblem(static_cast<int>(p.X.rows()), static_cast<int>(n + added), 3,
                                    problem_seed);
  std::vector<Eigen::Index> keep;
  for (Eigen::Index i = 0; i < n; ++i)
    if (drop == 0 || i % drop != 0) keep.push_back(i);
  Edited e;
  e.X.resize(p.X.rows(), static_cast<Eigen::Index>(keep.size()) + added);
  e.y.resize(e.X.cols());
  for (size_t s = 0; s < keep.size(); ++s) {
    e.X.col(s) = p.X.col(keep[s]);
    e.y[s] = y[keep[s]];
    e.previous_index.push_back(keep[s]);
  }
  for (int a = 0; a < added; ++a) {
    const Eigen::Index s = static_cast<Eigen::Index>(keep.size()) + a;
    e.X.col(s) = more.X.col(n + a);
    e.y[s] = more.labels[n + a] == 1 ? 1.0 : -1.0;
    e.previous_index.push_back(-1);
  }
  return e;
}

// A workspace carries the kernel columns of kept samples into the retrain and recomputes only the
// rows of new ones. Wrong rows would show as a different optimum or a KKT violation measured with
// exact kernel values; reuse shows as fewer kernel values computed.
TEST(WarmStart, WorkspaceKeepsColumnsAndReachesTheSameOptimum) {
  for (int d : {2, 6}) {
    const auto p = makeBallProblem(d, 3000, 3, 60 + d);
    const Eigen::VectorXd y = p.binary();
    const Kernel k = Kernel::rbfFromSigma(p.ball_radius / 2);
    const SolverOptions opt;
    const Eigen::VectorXd C = Eigen::VectorXd::Constant(y.size(), 10.0);
    // moved + removed + added and shuffled; only removed (kept samples past the new end move);
    // only added (the problem grows past the cached columns).
    const std::vector<Edited> edits = {edit(p, 60 + d, y, 0.05, 7),
                                       removeAndAdd(p, y, 7, 0, 60 + d),
                                       removeAndAdd(p, y, 0, 400, 60 + d)};
    for (size_t c = 0; c < edits.size(); ++c) {
      const Edited& e = edits[c];
      SolverWorkspace workspace;
      const SolverResult first = solveBinary(p.X, y, C, k, opt, nullptr, &workspace);
      EXPECT_EQ(first.workspace_solve, workspace.lastSolve());
      const WarmStart warm = makeWarmStart(p.X, y, C, k, first, e.previous_index);
      const Eigen::VectorXd C2 = Eigen::VectorXd::Constant(e.y.size(), 10.0);
      const SolverResult plain = solveBinary(e.X, e.y, C2, k, opt, &warm);
      const SolverResult kept = solveBinary(e.X, e.y, C2, k, opt, &warm, &workspace);
      SCOPED_TRACE("d=" + std::to_string(d) + " edit " + std::to_string(c));
      ASSERT_EQ(kept.status, SolverStatus::kOptimal);
      EXPECT_GT(kept.warm.reused_columns, 0);
      EXPECT_LT(kept.kernel_entries, plain.kernel_entries);
      EXPECT_NEAR(kept.objective, plain.objective, 1e-4 * std::abs(plain.objective));
      const Eigen::VectorXd G = testing::exactGradient(e.X, e.y, kept.alpha, k);
      EXPECT_LT(testing::kktViolation(e.y, C2, kept.alpha, G), 1.5 * opt.eps);
      EXPECT_NEAR(e.y.dot(kept.alpha), 0.0, 1e-9);
      // A warm start that does not continue the workspace's last solve reuses nothing.
      const SolverResult again = solveBinary(e.X, e.y, C2, k, opt, &warm, &workspace);
      EXPECT_EQ(again.warm.reused_columns, 0);
      EXPECT_NEAR(again.objective, plain.objective, 1e-4 * std::abs(plain.objective));
    }
  }
}

TEST(WarmStart, ColdSolveInAWorkspaceIsTheSameSolve) {
  const auto p = makeBallProblem(3, 1500, 3, 12);
  const Eigen::VectorXd y = p.binary();
  const Kernel k = Kernel::rbfFromSigma(p.ball_radius / 2);
  const Eigen::VectorXd C = Eigen::VectorXd::Constant(y.size(), 10.0);
  const SolverResult plain = solveBinary(p.X, y, C, k, {});
  SolverWorkspace workspace;
  for (int round = 0; round < 2; ++round) {  // the second one reuses the first one's memory
    const SolverResult r = solveBinary(p.X, y, C, k, {}, nullptr, &workspace);
    EXPECT_EQ(r.alpha, plain.alpha);
    EXPECT_EQ(r.iterations, plain.iterations);
    EXPECT_EQ(r.kernel_entries, plain.kernel_entries);
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
  const WarmStart warm = makeWarmStart(p.X, y, C, k, first, e.previous_index);
  ASSERT_EQ(warm.validate(e.X.cols(), e.X.rows(), k), "");
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
  const WarmStart warm = makeWarmStart(p.X, y, C, k, first, same);
  const SolverResult again = solveBinary(p.X, y, C, k, {}, &warm);
  EXPECT_EQ(again.iterations, 0);
  EXPECT_EQ(again.warm.columns, 0);
  EXPECT_NEAR(again.objective, first.objective, 1e-12 * std::abs(first.objective));
}

// A start no solve gives is refused, not taken: the solver had ended "optimal" from values like
// these, far from the optimum (a start from gamma 1 for gamma 4: objective off by 60%, KKT gap 19).
TEST(WarmStart, InconsistentStartsAreRefused) {
  const auto p = makeBallProblem(2, 100, 2, 4);
  const Eigen::VectorXd y = p.binary();
  const Eigen::VectorXd C = Eigen::VectorXd::Constant(100, 1.0);
  const Kernel k = Kernel::rbf(1.0);
  const SolverResult first = solveBinary(p.X, y, C, k, {});
  std::vector<Eigen::Index> same(100);
  std::iota(same.begin(), same.end(), 0);
  const WarmStart good = makeWarmStart(p.X, y, C, k, first, same);
  ASSERT_NO_THROW(solveBinary(p.X, y, C, k, {}, &good));
  const auto refused = [&](const WarmStart& w, const Kernel& kernel, const std::string& expected) {
    try {
      solveBinary(p.X, y, C, kernel, {}, &w);
      ADD_FAILURE() << "taken: " << expected;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
  };
  refused(makeWarmStart(p.X, y, C, k, first, std::vector<Eigen::Index>(100, 0)), k, "continued twice");
  refused(makeWarmStart(p.X, y, C, k, first, std::vector<Eigen::Index>(50, -1)), k, "previous_index has 50");
  refused(good, Kernel::rbf(4.0), "another kernel");
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const auto with = [&](auto change) {
    WarmStart w = good;
    change(w);
    return w;
  };
  refused(with([](WarmStart& w) { w.alpha = -w.alpha; }), k, "0 <= alpha <= C");
  refused(with([&](WarmStart& w) { w.alpha[3] = nan; }), k, "alpha nan");
  refused(with([](WarmStart& w) { w.alpha[3] = w.C[3] * 2; }), k, "0 <= alpha <= C");
  refused(with([&](WarmStart& w) { w.gradient[5] = nan; }), k, "gradient nan");
  refused(with([](WarmStart& w) { w.gradient_bound[5] = HUGE_VAL; }), k, "gradient_bound inf");
  refused(with([](WarmStart& w) { w.y[7] = 2; }), k, "y 2");
  refused(with([&](WarmStart& w) { w.X(0, 9) = nan; }), k, "coordinates not finite");
}

}  // namespace
}  // namespace svmp::svm
