// One-versus-rest on neighbourhoods with a fixed bias (svm/local_one_vs_rest.hpp): the solver reaches
// the optimum of its box-constrained dual (against projected gradient descent on the dense problem),
// leaving the far samples out is exact (every sample of the whole problem meets its KKT condition,
// and training on all samples gives the same models), and threads do not change the result.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <Eigen/Eigenvalues>

#include "svm/local_one_vs_rest.hpp"
#include "tests/svm/ball_problems.hpp"

namespace svmp::svm {
namespace {

// y_i F(x_i) for every sample, F summed over the model's support vectors with the truncated kernel.
Eigen::VectorXd margins(const BinaryModel& model, const Eigen::MatrixXd& X, const Eigen::VectorXd& y, double gamma) {
  Eigen::VectorXd out(X.cols());
  for (Eigen::Index i = 0; i < X.cols(); ++i) {
    double f = model.bias();
    for (int s = 0; s < model.numSupportVectors(); ++s) {
      const double k = std::exp(-gamma * (model.supportVectors().col(s) - X.col(i)).squaredNorm());
      f += k < std::exp(-5.0) ? 0.0 : model.coefficients()[s] * k;
    }
    out[i] = y[i] * f;
  }
  return out;
}

// KKT of the fixed-bias problem on all samples, neighbourhood or not: alpha = 0 -> y F >= 1,
// 0 < alpha < C -> y F = 1, alpha = C -> y F <= 1 (within the stopping tolerance, plus float columns).
TEST(LocalOneVsRest, EverySampleMeetsItsKktCondition) {
  const auto p = testing::makeBallProblem(3, 900, 4, 5);
  const Kernel k = Kernel::rbfFromSigma(p.ball_radius / 2);
  SolverOptions opt;
  opt.eps = 1e-4;
  const OneVsRestModel ovr = trainOneVsRestLocal(p.X, p.labels, k, 10.0, {}, opt, 1);
  const auto hoods = classNeighbourhoods(p.X, p.labels, ovr.classes, k);
  ASSERT_EQ(ovr.classes.size(), 4u);
  for (size_t c = 0; c < ovr.classes.size(); ++c) {
    EXPECT_LT(hoods[c].size(), p.X.cols()) << "class " << c << ": the test needs far samples";
    EXPECT_EQ(ovr.models[c].bias(), kLocalBias);
    Eigen::VectorXd y, C;
    oneVsRestProblem(p.labels, ovr.classes[c], 10.0, {}, y, C);
    const Eigen::VectorXd yf = margins(ovr.models[c], p.X, y, k.gamma);
    const Eigen::VectorXd& a = ovr.solutions[c].alpha;
    int far = 0;
    for (Eigen::Index i = 0; i < p.X.cols(); ++i) {
      const double tol = 1e-4 + 1e-5;
      if (a[i] <= 0) {
        EXPECT_GE(yf[i], 1 - tol) << "class " << c << " sample " << i;
      } else if (a[i] < C[i]) {
        EXPECT_NEAR(yf[i], 1, tol) << "class " << c << " sample " << i;
      } else {
        EXPECT_LE(yf[i], 1 + tol) << "class " << c << " sample " << i;
      }
      far += !std::binary_search(hoods[c].begin(), hoods[c].end(), static_cast<int>(i));
    }
    EXPECT_GT(far, 0);
  }
}

// Every sample in every class's problem: the same optimum (objective and decision values) as the
// neighbourhoods give, so the samples left out change nothing.
TEST(LocalOneVsRest, NeighbourhoodsGiveTheWholeProblemsOptimum) {
  const auto p = testing::makeBallProblem(2, 600, 3, 9);
  const Kernel k = Kernel::rbfFromSigma(p.ball_radius / 2);
  SolverOptions opt;
  opt.eps = 1e-6;
  const OneVsRestModel local = trainOneVsRestLocal(p.X, p.labels, k, 10.0, {{2, 3.0}}, opt, 1);
  std::vector<int> all(p.X.cols());
  for (int i = 0; i < static_cast<int>(all.size()); ++i) all[i] = i;
  const std::vector<std::vector<int>> everything(local.classes.size(), all);
  const OneVsRestModel whole = trainOneVsRestLocal(p.X, p.labels, k, 10.0, {{2, 3.0}}, opt, 1, &everything);
  for (size_t c = 0; c < local.classes.size(); ++c) {
    EXPECT_NEAR(local.solutions[c].objective, whole.solutions[c].objective, 1e-6 * std::abs(whole.solutions[c].objective));
    for (int t = 0; t < 50; ++t) {
      const Eigen::Vector2d q = Eigen::Vector2d::Random().cwiseAbs();
      EXPECT_NEAR(local.models[c].decision(q.data()), whole.models[c].decision(q.data()), 1e-4) << c;
    }
  }
}

// The coordinate descent's optimum against projected gradient descent on the dense dual
// (min 1/2 a'Qa - p'a, 0 <= a <= C, Q with the truncated kernel), with weighted C so that some
// alphas sit at their bound.
TEST(LocalOneVsRest, CoordinateDescentReachesTheDualOptimum) {
  const auto p = testing::makeBallProblem(2, 80, 2, 4);
  const Kernel k = Kernel::rbfFromSigma(p.ball_radius / 3);
  SolverOptions opt;
  opt.eps = 1e-8;
  const std::map<int, double> w = {{1, 0.05}};
  const OneVsRestModel ovr = trainOneVsRestLocal(p.X, p.labels, k, 1.0, w, opt, 1);
  Eigen::VectorXd y, C;
  oneVsRestProblem(p.labels, ovr.classes[0], 1.0, w, y, C);
  const Eigen::Index n = p.X.cols();
  Eigen::MatrixXd Q(n, n);
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = 0; j < n; ++j) {
      const double kij = std::exp(-k.gamma * (p.X.col(i) - p.X.col(j)).squaredNorm());
      Q(i, j) = y[i] * y[j] * (kij < std::exp(-5.0) ? 0.0 : kij);
    }
  const Eigen::VectorXd pv = (1.0 - kLocalBias * y.array()).matrix();
  Eigen::VectorXd a = Eigen::VectorXd::Zero(n);
  const double step = 1.0 / Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(Q).eigenvalues().maxCoeff();
  for (int it = 0; it < 200000; ++it) a = (a - step * (Q * a - pv)).cwiseMax(0.0).cwiseMin(C);
  const double best = 0.5 * a.dot(Q * a) - pv.dot(a);
  EXPECT_NEAR(ovr.solutions[0].objective, best, 1e-6 * std::abs(best));
  EXPECT_GT((a.array() >= C.array() - 1e-12).count(), 0) << "no alpha at its bound: the test lost its point";
}

TEST(LocalOneVsRest, ThreadsDoNotChangeTheModels) {
  const auto p = testing::makeBallProblem(3, 700, 5, 17);
  const Kernel k = Kernel::rbfFromSigma(p.ball_radius / 2);
  const OneVsRestModel one = trainOneVsRestLocal(p.X, p.labels, k, 10.0, {}, {}, 1);
  const OneVsRestModel two = trainOneVsRestLocal(p.X, p.labels, k, 10.0, {}, {}, 2);
  for (size_t c = 0; c < one.classes.size(); ++c) {
    EXPECT_EQ(one.solutions[c].alpha, two.solutions[c].alpha) << c;
    EXPECT_EQ(one.solutions[c].iterations, two.solutions[c].iterations) << c;
  }
}

// Neighbourhoods against brute force, and the search stopping once their share exceeds max_share.
TEST(LocalOneVsRest, NeighbourhoodsAgainstBruteForceAndTheirShare) {
  const auto p = testing::makeBallProblem(3, 400, 4, 7);
  const Kernel k = Kernel::rbfFromSigma(p.ball_radius / 2);
  const std::vector<int> classes = {1, 2, 3, 4};
  const auto hoods = classNeighbourhoods(p.X, p.labels, classes, k);
  ASSERT_EQ(hoods.size(), 4u);
  for (int c = 0; c < 4; ++c) {
    std::vector<int> expected;
    for (Eigen::Index i = 0; i < p.X.cols(); ++i) {
      bool near = false;
      for (Eigen::Index j = 0; j < p.X.cols() && !near; ++j)
        near = p.labels[j] == classes[c] && (p.X.col(i) - p.X.col(j)).squaredNorm() < 5.0 / k.gamma;
      if (near) expected.push_back(static_cast<int>(i));
    }
    EXPECT_EQ(hoods[c], expected) << "class " << c;
  }
  const double share = neighbourhoodShare(hoods, p.X.cols());
  ASSERT_GT(share, 0.0);
  ASSERT_LT(share, 1.0);
  EXPECT_TRUE(classNeighbourhoods(p.X, p.labels, classes, k, 0.99 * share).empty());
  EXPECT_EQ(classNeighbourhoods(p.X, p.labels, classes, k, 1.01 * share), hoods);
  EXPECT_DOUBLE_EQ(neighbourhoodShare({{0, 1}, {1, 2, 3}}, 4), (4.0 + 9.0) / (2 * 16.0));
}

TEST(LocalOneVsRest, BadInput) {
  const auto p = testing::makeBallProblem(2, 50, 2, 1);
  EXPECT_THROW(trainOneVsRestLocal(p.X, p.labels, Kernel::rbf(1.0), -1.0, {}, {}, 1), std::invalid_argument);
  Kernel poly;
  poly.type = KernelType::kPolynomial;
  EXPECT_THROW(trainOneVsRestLocal(p.X, p.labels, poly, 1.0, {}, {}, 1), std::invalid_argument);
  const std::vector<int> one_class(p.labels.size(), 1);
  EXPECT_THROW(trainOneVsRestLocal(p.X, one_class, Kernel::rbf(1.0), 1.0, {}, {}, 1), std::invalid_argument);
}

}  // namespace
}  // namespace svmp::svm

namespace svmp::svm {
namespace {

// A time limit already past (SolverOptions::stop true) ends both trainings at once: every class
// reports kStopped instead of training on (the local planner's 257 ms of training at a 50 ms limit).
TEST(LocalOneVsRest, APassedLimitStopsEveryClassOfBothTrainings) {
  const auto p = testing::makeBallProblem(3, 600, 4, 5);
  const Kernel k = Kernel::rbfFromSigma(p.ball_radius / 2);
  SolverOptions opt;
  opt.stop = [] { return true; };
  for (const OneVsRestModel& ovr : {trainOneVsRestLocal(p.X, p.labels, k, 10.0, {}, opt, 1),
                                    trainOneVsRest(p.X, p.labels, k, 10.0, {}, opt, 2)})
    for (const SolverResult& s : ovr.solutions) {
      EXPECT_EQ(s.status, SolverStatus::kStopped);
      EXPECT_EQ(s.alpha.size(), p.X.cols());
    }
  opt.stop = [] { return false; };
  for (const SolverResult& s : trainOneVsRest(p.X, p.labels, k, 10.0, {}, opt, 1).solutions)
    EXPECT_EQ(s.status, SolverStatus::kOptimal);
}

}  // namespace
}  // namespace svmp::svm
