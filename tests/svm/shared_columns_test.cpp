// Shared kernel columns (svm/shared_columns.hpp): the kernel's values, each column computed once
// whatever the threads, solves with them the solves without them, and columns of other samples refused.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <stdexcept>
#include <vector>

#include "svm/shared_columns.hpp"
#include "svm/smo_solver.hpp"
#include "tests/svm/ball_problems.hpp"
#include "tests/svm/test_helpers.hpp"

namespace svmp::svm {
namespace {

TEST(SharedColumns, HoldTheKernelAndComputeEachColumnOnce) {
  const auto p = testing::makeBallProblem(6, 700, 3, 41);
  const Kernel k = Kernel::rbfFromSigma(p.ball_radius / 2);
  const int n = 700, d = 6;
  SharedColumns serial(p.X, k);
  for (int s : {0, 1, 350, 699}) {
    const float* col = serial.column(s);
    for (int t = 0; t < n; ++t) {
      const double exact = k.value(p.X.col(s).data(), p.X.col(t).data(), d);
      ASSERT_NEAR(col[t], exact, 1e-6 * exact + 1e-30) << s << " " << t;
    }
    EXPECT_EQ(serial.column(s), col);  // asked again: the same column, not computed again
  }
  EXPECT_EQ(serial.computedColumns(), 4);
  for (int s = 0; s < n; ++s) serial.column(s);
  EXPECT_EQ(serial.computedColumns(), n);

  // Two threads asking for every column, in opposite orders: each computed once, the same values.
  SharedColumns raced(p.X, k);
#pragma omp parallel for num_threads(2)
  for (int thread = 0; thread < 2; ++thread)
    for (int i = 0; i < n; ++i) raced.column(thread == 0 ? i : n - 1 - i);
  EXPECT_EQ(raced.computedColumns(), n);
  for (int s = 0; s < n; ++s)
    ASSERT_EQ(std::memcmp(raced.column(s), serial.column(s), n * sizeof(float)), 0) << s;
}

// With shrinking off the columns are read in place; with it on they are gathered in the solver's
// permutation. Either way the solve is the one without shared columns.
TEST(SharedColumns, SolveIsTheSolveWithoutThem) {
  const auto p = testing::makeBallProblem(6, 1500, 3, 42);
  const Kernel k = Kernel::rbfFromSigma(p.ball_radius / 2);
  const Eigen::VectorXd y = p.binary(2);
  const Eigen::VectorXd C = Eigen::VectorXd::Constant(y.size(), 10.0);
  for (const bool shrinking : {false, true}) {
    SolverOptions opt;
    opt.shrinking = shrinking;
    const SolverResult alone = solveBinary(p.X, y, C, k, opt);
    SharedColumns shared(p.X, k);
    const SolverResult with = solveBinary(p.X, y, C, k, opt, nullptr, nullptr, &shared);
    EXPECT_NEAR(with.objective, alone.objective, 1e-7 * std::abs(alone.objective)) << shrinking;
    EXPECT_LE(with.violation, opt.eps);
    const Eigen::VectorXd G = testing::exactGradient(p.X, y, with.alpha, k);
    EXPECT_LE(testing::kktViolation(y, C, with.alpha, G), 2 * opt.eps) << shrinking;
    EXPECT_NEAR(with.support_vectors, alone.support_vectors, 0.01 * alone.support_vectors) << shrinking;
    EXPECT_EQ(with.kernel_entries > 0, shrinking);  // in place: no column copied into a cache
  }
}

TEST(SharedColumns, OfOtherSamplesOrKernelAreRejected) {
  const auto p = testing::makeBallProblem(3, 200, 2, 43);
  const Kernel k = Kernel::rbfFromSigma(p.ball_radius / 2);
  const Eigen::VectorXd y = p.binary();
  const Eigen::VectorXd C = Eigen::VectorXd::Constant(y.size(), 10.0);
  SharedColumns shared(p.X, k);
  Eigen::MatrixXd moved = p.X;
  moved(1, 17) += 1e-9;
  EXPECT_THROW(solveBinary(moved, y, C, k, {}, nullptr, nullptr, &shared), std::invalid_argument);
  EXPECT_THROW(solveBinary(p.X, y, C, Kernel::rbfFromSigma(p.ball_radius), {}, nullptr, nullptr, &shared),
               std::invalid_argument);
  EXPECT_NO_THROW(solveBinary(p.X, y, C, k, {}, nullptr, nullptr, &shared));
}

}  // namespace
}  // namespace svmp::svm
