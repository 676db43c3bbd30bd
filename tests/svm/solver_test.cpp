#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "svm/model.hpp"
#include "svm/smo_parallel.hpp"
#include "svm/smo_solver.hpp"
#include "tests/svm/ball_problems.hpp"
#include "tests/svm/test_helpers.hpp"
#ifdef SVMP_HAVE_LIBSVM
#include "tests/svm/libsvm_oracle.hpp"
#endif

namespace svmp::svm {
namespace {

using testing::exactGradient;
using testing::exactObjective;
using testing::kktViolation;
using testing::makeBallProblem;

constexpr double kC = 10.0;
double sigmaFor(const testing::BallProblem& p) { return p.ball_radius / 2; }

std::string what(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "(no exception)";
}

TEST(Solver, SolutionSatisfiesKktToEps) {
  for (int d : {2, 6}) {
    const auto p = makeBallProblem(d, 3000, 3, 11 + d);
    const Eigen::VectorXd y = p.binary();
    const Eigen::VectorXd C = Eigen::VectorXd::Constant(y.size(), kC);
    const Kernel k = Kernel::rbfFromSigma(sigmaFor(p));
    SolverOptions opt;
    const SolverResult r = solveBinary(p.X, y, C, k, opt);
    ASSERT_EQ(r.status, SolverStatus::kOptimal);
    EXPECT_NEAR(y.dot(r.alpha), 0.0, 1e-9);
    EXPECT_GE(r.alpha.minCoeff(), 0.0);
    EXPECT_LE((r.alpha - C).maxCoeff(), 0.0);
    EXPECT_LT(r.violation, opt.eps);
    const Eigen::VectorXd G = exactGradient(p.X, y, r.alpha, k);
    // The solver's gradient accumulates float kernel columns; the exact one may differ slightly.
    EXPECT_LT((G - r.gradient).cwiseAbs().maxCoeff(), 1e-4);
    EXPECT_LT(kktViolation(y, C, r.alpha, G), opt.eps) << "d=" << d;
    EXPECT_NEAR(r.objective, exactObjective(r.alpha, G), 1e-6 * std::abs(r.objective));
    EXPECT_GT(r.support_vectors, 0);
  }
}

// Shrinking from the start reaches the same optimum (KKT to eps against the exact gradient) over a
// smaller mean active set where few samples are support vectors.
TEST(Solver, EarlyShrinkingReachesKktOverFewerSamples) {
  const auto p = makeBallProblem(3, 2500, 3, 31);
  const Eigen::VectorXd y = p.binary();
  const Eigen::VectorXd C = Eigen::VectorXd::Constant(y.size(), kC);
  const Kernel k = Kernel::rbfFromSigma(sigmaFor(p));
  SolverOptions early;
  early.early_shrinking = true;
  const SolverResult r = solveBinary(p.X, y, C, k, early), base = solveBinary(p.X, y, C, k, {});
  ASSERT_EQ(r.status, SolverStatus::kOptimal);
  ASSERT_LT(base.support_vectors, y.size() / 4);
  const Eigen::VectorXd G = exactGradient(p.X, y, r.alpha, k);
  EXPECT_LT(kktViolation(y, C, r.alpha, G), early.eps);
  EXPECT_NEAR(r.objective, base.objective, 1e-3 * std::abs(base.objective));
  EXPECT_LT(r.mean_active, 0.8 * base.mean_active);
}

TEST(Solver, OtherKernelsReachKkt) {
  const auto p = makeBallProblem(4, 600, 2, 5);
  const Eigen::VectorXd y = p.binary();
  const Eigen::VectorXd C = Eigen::VectorXd::Constant(y.size(), 1.0);
  Kernel poly;
  poly.type = KernelType::kPolynomial;
  poly.gamma = 1.0;
  poly.coef0 = 1.0;
  poly.degree = 3;
  Kernel rq;
  rq.type = KernelType::kRationalQuadratic;
  rq.gamma = 20.0;
  Kernel sig;  // indefinite: exercises the tau safeguard
  sig.type = KernelType::kSigmoid;
  sig.gamma = 0.5;
  sig.coef0 = -1.0;
  for (const Kernel& k : {poly, rq, sig, Kernel::blockSum(Kernel::rbfFromSigma(0.1), 2)}) {
    SolverOptions opt;
    opt.max_iterations = 200000;
    const SolverResult r = solveBinary(p.X, y, C, k, opt);
    const Eigen::VectorXd G = exactGradient(p.X, y, r.alpha, k);
    EXPECT_NEAR(y.dot(r.alpha), 0.0, 1e-9);
    if (k.type != KernelType::kSigmoid) {
      ASSERT_EQ(r.status, SolverStatus::kOptimal) << kernelTypeName(k.type);
      EXPECT_LT(kktViolation(y, C, r.alpha, G), opt.eps) << kernelTypeName(k.type);
    }
  }
}

TEST(Solver, TinyCacheGivesTheSameSolution) {
  const auto p = makeBallProblem(3, 1501, 3, 21);  // odd: columns have a scalar tail
  const Eigen::VectorXd y = p.binary(2);
  const Eigen::VectorXd C = Eigen::VectorXd::Constant(y.size(), kC);
  const Kernel k = Kernel::rbfFromSigma(sigmaFor(p));
  SolverOptions big, tiny;
  tiny.cache_mb = 0;  // two columns: every swap/evict path runs
  big.eps = tiny.eps = 1e-6;
  const SolverResult a = solveBinary(p.X, y, C, k, big);
  const SolverResult b = solveBinary(p.X, y, C, k, tiny);
  EXPECT_NEAR(a.objective, b.objective, 1e-9 * std::abs(a.objective));
  EXPECT_GT(b.cache_misses, a.cache_misses);
  // Bit for bit: a column resumed from a partly cached one has its entries computed by other lanes
  // (vector body or scalar tail), and they must agree.
  EXPECT_EQ(a.iterations, b.iterations);
  EXPECT_EQ(a.bias, b.bias);
  EXPECT_TRUE(a.alpha == b.alpha);
  SolverOptions noshrink = big;
  noshrink.shrinking = false;
  const SolverResult c = solveBinary(p.X, y, C, k, noshrink);
  EXPECT_NEAR(a.objective, c.objective, 1e-9 * std::abs(a.objective));
}

// Threads split the loops of every iteration (forced at any size here); the element-wise parts give
// the same bits, so the solve follows the same path unless selectJ meets an exact-rounding tie.
TEST(Solver, ThreadsGiveTheSameSolution) {
  const auto p = makeBallProblem(3, 300, 3, 23);  // small: a busy machine makes each barrier slow
  const Eigen::VectorXd y = p.binary(1);
  const Eigen::VectorXd C = Eigen::VectorXd::Constant(y.size(), kC);
  const Kernel k = Kernel::rbfFromSigma(sigmaFor(p));
  SolverOptions one, two;
  two.threads = 2;
  two.parallel_min_samples = 8;
  const SolverResult a = solveBinary(p.X, y, C, k, one);
  const SolverResult b = solveBinary(p.X, y, C, k, two);
  EXPECT_NEAR(a.objective, b.objective, 1e-6 * std::abs(a.objective));
  EXPECT_EQ(a.support_vectors, b.support_vectors);
  EXPECT_LT((a.alpha - b.alpha).cwiseAbs().maxCoeff(), 1e-3 * kC);
  const SolverResult again = solveBinary(p.X, y, C, k, two);  // same thread count, same result
  EXPECT_EQ(again.alpha, b.alpha);
  two.threads = 0;
  EXPECT_THROW(solveBinary(p.X, y, C, k, two), std::invalid_argument);
}

// An exception in one chunk of a parallel loop reaches the caller (the lowest chunk's first); one
// leaving the OpenMP region would end the program.
TEST(Solver, AChunkThatThrowsReachesTheCaller) {
  const auto throwIn = [](int which) {
    return [which](int, int, int chunk) {
      if (which < 0 || chunk == which) throw std::runtime_error("chunk " + std::to_string(chunk));
    };
  };
  EXPECT_THROW(parallel::forChunks(64, 2, 8, throwIn(1)), std::runtime_error);
  try {
    parallel::forChunks(64, 2, 8, throwIn(-1));
    ADD_FAILURE() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "chunk 0");
  }
  // Without a failure every entry is visited once.
  std::vector<int> visits(64, 0);
  parallel::forChunks(64, 2, 8, [&](int begin, int end, int) {
    for (int i = begin; i < end; ++i) ++visits[static_cast<size_t>(i)];
  });
  EXPECT_EQ(visits, std::vector<int>(64, 1));
}

// A time limit's hook: polled every 1,000 iterations, it ends the solve with the iterate reached.
TEST(Solver, AStopEndsTheSolve) {
  const auto p = makeBallProblem(6, 3000, 3, 17);  // as SolutionSatisfiesKktToEps: thousands of iterations
  const Eigen::VectorXd C = Eigen::VectorXd::Constant(3000, kC);
  SolverOptions opt;
  const SolverResult full = solveBinary(p.X, p.binary(), C, Kernel::rbfFromSigma(sigmaFor(p)), opt);
  ASSERT_GT(full.iterations, 1000) << "test premise: the solve outlasts the first poll after 0";
  int polls = 0;
  opt.stop = [&] { return ++polls > 1; };
  const SolverResult r = solveBinary(p.X, p.binary(), C, Kernel::rbfFromSigma(sigmaFor(p)), opt);
  EXPECT_EQ(r.status, SolverStatus::kStopped) << r.report();
  // Polls at iteration 0 (false), then after 1,000 iterations or 2^20 gradient entries (true).
  EXPECT_GT(r.iterations, (1L << 20) / 3000 - 1);
  EXPECT_LE(r.iterations, 1000);
  EXPECT_EQ(polls, 2);
  // The iterate, without the end's gradient reconstruction; no warm start from it.
  EXPECT_EQ(r.alpha.size(), 3000);
  EXPECT_EQ(r.gradient.size(), 0);
  EXPECT_TRUE(std::isnan(r.objective));
  EXPECT_THROW(makeWarmStart(p.X, p.binary(), C, Kernel::rbfFromSigma(sigmaFor(p)), r, {}),
               std::invalid_argument);
}

TEST(Solver, IterationLimitIsReported) {
  const auto p = makeBallProblem(2, 2000, 3, 3);
  SolverOptions opt;
  opt.max_iterations = 10;
  const SolverResult r = solveBinary(p.X, p.binary(), Eigen::VectorXd::Constant(2000, kC),
                                     Kernel::rbfFromSigma(0.1), opt);
  EXPECT_EQ(r.status, SolverStatus::kIterationLimit);
  EXPECT_EQ(r.iterations, 10);
  EXPECT_NEAR(p.binary().dot(r.alpha), 0.0, 1e-12);
}

TEST(Solver, BadInputThrowsWithAReason) {
  const auto p = makeBallProblem(2, 50, 2, 1);
  const Eigen::VectorXd y = p.binary();
  const Eigen::VectorXd C = Eigen::VectorXd::Constant(50, 1.0);
  const Kernel k = Kernel::rbfFromSigma(0.3);
  const SolverOptions opt;
  auto solve = [&](const Eigen::MatrixXd& X, const Eigen::VectorXd& yy, const Eigen::VectorXd& CC,
                   const Kernel& kk,
                   const SolverOptions& o) { return [=] { solveBinary(X, yy, CC, kk, o); }; };
  EXPECT_NE(what(solve(p.X, Eigen::VectorXd::Ones(50), C, k, opt)).find("only class +1"),
            std::string::npos);
  EXPECT_NE(what(solve(p.X, -Eigen::VectorXd::Ones(50), C, k, opt)).find("only class -1"),
            std::string::npos);
  EXPECT_NE(what(solve(Eigen::MatrixXd(2, 0), Eigen::VectorXd(0), Eigen::VectorXd(0), k, opt))
                .find("no samples"),
            std::string::npos);
  EXPECT_NE(what(solve(p.X, y.head(49), C, k, opt)).find("49 labels"), std::string::npos);
  EXPECT_NE(what(solve(p.X, y, C.head(10), k, opt)).find("C has 10"), std::string::npos);
  Eigen::MatrixXd Xnan = p.X;
  Xnan(1, 7) = std::nan("");
  EXPECT_NE(what(solve(Xnan, y, C, k, opt)).find("NaN"), std::string::npos);
  Eigen::MatrixXd Xinf = p.X;
  Xinf(0, 3) = INFINITY;
  EXPECT_NE(what(solve(Xinf, y, C, k, opt)).find("Inf"), std::string::npos);
  Eigen::VectorXd Cbad = C;
  Cbad[4] = 0;
  EXPECT_NE(what(solve(p.X, y, Cbad, k, opt)).find("C[4]"), std::string::npos);
  Eigen::VectorXd ybad = y;
  ybad[2] = 0.5;
  EXPECT_NE(what(solve(p.X, ybad, C, k, opt)).find("+1 or -1"), std::string::npos);
  Kernel kbad = k;
  kbad.gamma = 0;
  EXPECT_NE(what(solve(p.X, y, C, kbad, opt)).find("gamma"), std::string::npos);
  SolverOptions obad;
  obad.eps = -1;
  EXPECT_NE(what(solve(p.X, y, C, k, obad)).find("eps"), std::string::npos);
  EXPECT_NE(obad.validate(), "");
  EXPECT_EQ(opt.validate(), "");
}

TEST(Model, GradientMatchesCentralDifferences) {
  const auto p = makeBallProblem(3, 400, 2, 9);
  const Eigen::VectorXd y = p.binary();
  const Eigen::VectorXd C = Eigen::VectorXd::Constant(y.size(), kC);
  Kernel rq;
  rq.type = KernelType::kRationalQuadratic;
  rq.gamma = 30;
  for (const Kernel& k :
       {Kernel::rbfFromSigma(0.1), rq, Kernel::blockSum(Kernel::rbfFromSigma(0.1), 1)}) {
    const SolverResult r = solveBinary(p.X, y, C, k, SolverOptions());
    const BinaryModel m = BinaryModel::fromSolution(p.X, y, r, k);
    EXPECT_EQ(m.numSupportVectors(), r.support_vectors);
    EXPECT_EQ(m.dim(), 3);
    const Eigen::MatrixXd Q = testing::nearQueries(p.X, 20, 0.05, 4);
    for (int s = 0; s < Q.cols(); ++s) {
      double g[3];
      const double f = m.decisionAndGradient(Q.col(s).data(), g);
      EXPECT_NEAR(f, m.decision(Q.col(s).data()), 1e-12 * (1 + std::abs(f)));
      for (int i = 0; i < 3; ++i) {
        Eigen::VectorXd qp = Q.col(s), qm = Q.col(s);
        const double h = 1e-6;
        qp[i] += h;
        qm[i] -= h;
        const double fd = (m.decision(qp.data()) - m.decision(qm.data())) / (2 * h);
        EXPECT_NEAR(g[i], fd, 1e-5 * (1 + std::abs(fd)));
      }
    }
  }
}

#ifdef SVMP_HAVE_LIBSVM

struct Compared {
  SolverResult ours;
  testing::LibsvmResult theirs;
  double obj_ours, obj_theirs;  // exact recomputation from the alphas
};

Compared compare(const testing::BallProblem& p, const Eigen::VectorXd& y, double eps) {
  const Kernel k = Kernel::rbfFromSigma(sigmaFor(p));
  SolverOptions opt;
  opt.eps = eps;
  Compared c;
  c.ours = solveBinary(p.X, y, Eigen::VectorXd::Constant(y.size(), kC), k, opt);
  testing::LibsvmProblem prob(p.X, y);
  c.theirs = testing::libsvmTrain(prob, y, k.gamma, kC, eps);
  c.obj_ours = exactObjective(c.ours.alpha, exactGradient(p.X, y, c.ours.alpha, k));
  c.obj_theirs = exactObjective(c.theirs.alpha, exactGradient(p.X, y, c.theirs.alpha, k));
  return c;
}

// At eps = 1e-3 two solvers agree to ~eps * sum(alpha) in objective, so 1e-5 relative needs an
// objective that is not tiny: the planar problems use overlapping balls (r = 0.2, many bounded
// SVs). The separable planar problems are compared at eps = 1e-8 below.
TEST(SolverVsLibsvm, ObjectiveAtDefaultEps) {
  for (auto [d, n] : {std::pair{2, 2000}, std::pair{2, 5000}, std::pair{6, 5000}}) {
    const auto p = makeBallProblem(d, n, 3, 100 + d + n, 4, 0.2);
    const Compared c = compare(p, p.binary(), 1e-3);
    EXPECT_NEAR(c.obj_ours, c.obj_theirs, 1e-5 * std::abs(c.obj_theirs)) << "d=" << d << " n=" << n;
    EXPECT_NEAR(c.ours.objective, c.obj_ours, 1e-6 * std::abs(c.obj_ours));
  }
}

TEST(SolverVsLibsvm, ObjectiveAtDefaultEpsLarge) {
  const auto p = makeBallProblem(6, 20000, 3, 2020);
  const Compared c = compare(p, p.binary(), 1e-3);
  EXPECT_NEAR(c.ours.objective, c.obj_theirs, 1e-5 * std::abs(c.obj_theirs));
}

TEST(SolverVsLibsvm, TightEpsSameObjectiveAndSupportSet) {
  for (auto [d, n] : {std::pair{2, 2000}, std::pair{2, 5000}, std::pair{6, 3000}}) {
    const auto p = makeBallProblem(d, n, 3, 300 + d + n);
    const Compared c = compare(p, p.binary(), 1e-8);
    EXPECT_NEAR(c.obj_ours, c.obj_theirs, 1e-8 * std::abs(c.obj_theirs)) << "d=" << d;
    int differ = 0;
    for (Eigen::Index i = 0; i < c.ours.alpha.size(); ++i)
      differ += (c.ours.alpha[i] > 1e-6 * kC) != (c.theirs.alpha[i] > 1e-6 * kC);
    EXPECT_EQ(differ, 0) << "d=" << d;
    EXPECT_NEAR(c.ours.bias, c.theirs.bias, 1e-5);
  }
}

TEST(SolverVsLibsvm, DecisionsAgreeInSign) {
  const auto p = makeBallProblem(6, 3000, 3, 77);
  const Eigen::VectorXd y = p.binary();
  const Kernel k = Kernel::rbfFromSigma(sigmaFor(p));
  const SolverResult r = solveBinary(p.X, y, Eigen::VectorXd::Constant(y.size(), kC), k, {});
  const BinaryModel m = BinaryModel::fromSolution(p.X, y, r, k);
  testing::LibsvmProblem prob(p.X, y);
  testing::LibsvmModelPtr lib;
  testing::libsvmTrain(prob, y, k.gamma, kC, 1e-3, true, {}, &lib);
  const Eigen::MatrixXd Q = testing::nearQueries(p.X, 100000, sigmaFor(p) / 2, 8);
  int agree = 0;
  for (int s = 0; s < Q.cols(); ++s)
    agree += (m.decision(Q.col(s).data()) > 0) ==
             (testing::libsvmDecision(lib.get(), Q.col(s).data(), 6) > 0);
  EXPECT_GE(agree, 99990);
}

#endif  // SVMP_HAVE_LIBSVM

}  // namespace
}  // namespace svmp::svm
