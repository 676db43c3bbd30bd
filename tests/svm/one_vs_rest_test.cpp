#include <gtest/gtest.h>

#include <stdexcept>

#include "svm/one_vs_rest.hpp"
#include "tests/svm/ball_problems.hpp"
#include "tests/svm/test_helpers.hpp"
#ifdef SVMP_HAVE_LIBSVM
#include "tests/svm/libsvm_oracle.hpp"
#endif

namespace svmp::svm {
namespace {

// Each class is the binary problem solved alone with the options the training used: the first with
// shrinking, the others without it when they shared columns (svm/shared_columns.hpp), from the
// start when the first kept few support vectors. The same whatever the thread count.
void expectSeparateSolves(const testing::BallProblem& p, const Kernel& k, double C,
                          const std::map<int, double>& w, const SolverOptions& opt, long long shared,
                          bool early) {
  const OneVsRestModel one = trainOneVsRest(p.X, p.labels, k, C, w, opt, 1);
  const OneVsRestModel two = trainOneVsRest(p.X, p.labels, k, C, w, opt, 2);
  EXPECT_EQ(one.shared_columns, shared);
  EXPECT_EQ(two.shared_columns, shared);
  EXPECT_EQ(one.early_shrinking, early);
  EXPECT_EQ(two.early_shrinking, early);
  for (size_t c = 0; c < one.classes.size(); ++c) {
    Eigen::VectorXd y, sample_C;
    oneVsRestProblem(p.labels, one.classes[c], C, w, y, sample_C);
    SolverOptions alone = opt;
    alone.shrinking = c == 0 || shared == 0;
    alone.early_shrinking = c > 0 && early;
    const SolverResult r = solveBinary(p.X, y, sample_C, k, alone);
    EXPECT_NEAR(one.solutions[c].objective, r.objective, 1e-9 * std::abs(r.objective)) << c;
    EXPECT_NEAR(two.solutions[c].objective, r.objective, 1e-9 * std::abs(r.objective)) << c;
    EXPECT_EQ(one.models[c].numSupportVectors(), r.support_vectors) << c;
    EXPECT_EQ(two.models[c].numSupportVectors(), r.support_vectors) << c;
  }
}

// Three classes in 3-D whose problems each need a small part of the kernel matrix and keep few
// support vectors: no sharing, and the second and third shrink from the start.
TEST(OneVsRest, MatchesSeparateBinaryProblemsAndThreadCounts) {
  const auto p = testing::makeBallProblem(3, 2500, 3, 31);
  const Kernel k = Kernel::rbfFromSigma(p.ball_radius / 2);
  const std::map<int, double> w = {{1, 2.0}, {3, 0.5}};
  const OneVsRestModel ovr = trainOneVsRest(p.X, p.labels, k, 5.0, w, {}, 1);
  ASSERT_EQ(ovr.classes, (std::vector<int>{1, 2, 3}));
  Eigen::VectorXd y, C;
  oneVsRestProblem(p.labels, 1, 5.0, w, y, C);
  EXPECT_EQ(C[0], 10.0);  // sample 0 is class 1
  EXPECT_LT(ovr.solutions[0].support_vectors, 2500 / 4);
  EXPECT_TRUE(ovr.early_shrinking);
  expectSeparateSolves(p, k, 5.0, w, {}, 0, true);
}

// Interleaved classes in 7-D (as an arm's C-obstacles): each problem needs most of the kernel
// matrix, so the problems after the first share it, each column computed once. Without room for
// the matrix in cache_mb they do not.
TEST(OneVsRest, InterleavedClassesShareTheirColumns) {
  const auto p = testing::makeBallProblem(7, 1200, 8, 33, 4, 0.2);
  const Kernel k = Kernel::rbfFromSigma(0.1);  // about 800 support vectors a class, as panda_shelf's
  const OneVsRestModel ovr = trainOneVsRest(p.X, p.labels, k, 100.0, {}, {}, 1);
  ASSERT_EQ(ovr.classes.size(), 8u);
  EXPECT_GT(ovr.shared_columns, 600);
  EXPECT_LE(ovr.shared_columns, 1200);
  EXPECT_FALSE(ovr.early_shrinking);
  expectSeparateSolves(p, k, 100.0, {}, {}, ovr.shared_columns, false);
  SolverOptions small;
  small.cache_mb = 5;  // 1,200^2 floats are 5.5 MB
  expectSeparateSolves(p, k, 100.0, {}, small, 0, false);
}

TEST(OneVsRest, BadInputThrows) {
  const auto p = testing::makeBallProblem(2, 100, 3, 1);
  const Kernel k = Kernel::rbfFromSigma(0.1);
  EXPECT_THROW(trainOneVsRest(p.X, std::vector<int>(100, 1), k, 1.0, {}, {}, 1),
               std::invalid_argument);
  EXPECT_THROW(trainOneVsRest(p.X, std::vector<int>(99, 1), k, 1.0, {}, {}, 1),
               std::invalid_argument);
  EXPECT_THROW(trainOneVsRest(p.X, p.labels, k, -1.0, {}, {}, 1), std::invalid_argument);
  EXPECT_THROW(trainOneVsRest(p.X, p.labels, k, 1.0, {{2, 0.0}}, {}, 1), std::invalid_argument);
}

#ifdef SVMP_HAVE_LIBSVM
// libsvm has per-class weights only, so a weighted OvR problem is a libsvm problem when the
// "rest" classes share one weight: weights {class 1: 2.5} make problem 1 expressible (C+ = 2.5C,
// C- = C); the unweighted problems are checked for every class.
TEST(OneVsRestVsLibsvm, MatchesSeparateLibsvmRuns) {
  const auto p = testing::makeBallProblem(6, 3000, 3, 32);
  const Kernel k = Kernel::rbfFromSigma(p.ball_radius / 2);
  const double C = 10.0;
  for (const std::map<int, double>& w :
       {std::map<int, double>{}, std::map<int, double>{{1, 2.5}}}) {
    const OneVsRestModel ovr = trainOneVsRest(p.X, p.labels, k, C, w, {}, 2);
    for (int c = 0; c < 3; ++c) {
      if (!w.empty() && ovr.classes[c] != 1) continue;
      Eigen::VectorXd y, sample_C;
      oneVsRestProblem(p.labels, ovr.classes[c], C, w, y, sample_C);
      testing::LibsvmProblem prob(p.X, y);
      std::map<int, double> lib_w;
      if (!w.empty()) lib_w[1] = 2.5;
      const auto lib = testing::libsvmTrain(prob, y, k.gamma, C, 1e-3, true, lib_w);
      const double obj_lib =
          testing::exactObjective(lib.alpha, testing::exactGradient(p.X, y, lib.alpha, k));
      EXPECT_NEAR(ovr.solutions[c].objective, obj_lib, 1e-5 * std::abs(obj_lib))
          << "class " << ovr.classes[c] << " weighted " << !w.empty();
      EXPECT_NEAR(ovr.models[c].bias(), lib.bias, 2e-2);
    }
  }
}
#endif

}  // namespace
}  // namespace svmp::svm
