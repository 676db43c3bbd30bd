// SMO solver for the C-SVC dual (thesis ch. 2.1, eq. 2.10 with box 0 <= alpha_i <= C_i, eq. 2.16):
//   min_alpha 0.5 alpha' Q alpha - e' alpha,  Q_ij = y_i y_j k(x_i, x_j),  y' alpha = 0.
//
// Working-set selection: second-order WSS2 of Fan, Chen, Lin, "Working set selection using second
// order information for training SVM", JMLR 6 (2005), with libsvm's safeguard tau = 1e-12 for
// non-positive curvature (needed for indefinite kernels, e.g. a truncated or sigmoid Gram matrix).
// Shrinking, gradient reconstruction and the bias follow Chang & Lin, "LIBSVM: a library for
// support vector machines", ACM TIST 2 (2011), sec. 4.1.2 (stopping), 5.1 (shrinking) and 4.1.5
// (bias). Stops when the maximal violating pair gap m(alpha) - M(alpha) < eps.
//
// Thread-safety: solveBinary has no shared state; several calls may run concurrently.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

#include "svm/kernel.hpp"
#include "svm/solver_workspace.hpp"
#include "svm/warm_start.hpp"

namespace svmp::svm {

class SharedColumns;

struct SolverOptions {
  double eps = 1e-3;                 // stopping tolerance on the maximal violating pair gap
  long max_iterations = 10'000'000;  // reported as SolverStatus::kIterationLimit when reached
  double cache_mb = 100;             // kernel column cache (float entries)
  bool shrinking = true;
  // Shrink every 100 iterations from the start, as after a warm start, instead of libsvm's first
  // shrink after min(n, 1000): pays where few samples become support vectors (one-versus-rest of a
  // class far from most samples), costs gradient reconstructions where most do.
  bool early_shrinking = false;
  // Threads inside one solve (OpenMP), used while the active set has at least parallel_min_samples
  // samples (measured threshold: docs/benchmarks.md). 1 for solves that already run in parallel,
  // e.g. one-versus-rest across classes.
  int threads = 1;
  int parallel_min_samples = 8192;
  // Polled every 1,000 iterations when set, and sooner on large active sets (every 2^20 gradient
  // entries updated); a solve it ends reports SolverStatus::kStopped with the iterate it reached:
  // alpha and bias, but no gradient (empty), objective or violation (NaN), and no warm start from it
  // (a time limit's hook: one solve of 20,000 samples can take seconds).
  std::function<bool()> stop;

  std::string validate() const;  // "" when OK, else what is wrong
};

enum class SolverStatus { kOptimal, kIterationLimit, kStopped };

struct SolverResult {
  Eigen::VectorXd alpha;  // dual variables, original sample order
  double bias = 0.0;      // b of F(q) = sum_i y_i alpha_i k(x_i, q) + b; libsvm's -rho
  // Dual objective as libsvm reports it: 0.5 alpha'Q alpha - e'alpha (the negative of eq. 2.10).
  double objective = 0.0;
  long iterations = 0;
  SolverStatus status = SolverStatus::kOptimal;
  Eigen::VectorXd gradient;         // G = Q alpha - e (all samples, reconstructed at the end)
  Eigen::VectorXd gradient_bound;   // G_bar = sum over alpha_j = C_j of C_j Q_j (for warm start)
  double violation = 0.0;           // final m(alpha) - M(alpha)
  int support_vectors = 0;          // alpha_i > 0
  int bounded_support_vectors = 0;  // alpha_i = C_i
  long long cache_hits = 0, cache_misses = 0;
  long long kernel_entries = 0;  // kernel values computed for the cache (the solver's main cost)
  double mean_active = 0;        // active set size per iteration (shrinking), mean
  WarmStartCounts warm;  // what the warm start changed (zero for a cold start)
  long long workspace_solve = 0;  // SolverWorkspace::lastSolve() after this solve (0: none given)

  std::string report() const;  // one line
};

// Throws std::invalid_argument for bad input (sizes, NaN/Inf, labels not +-1, one class only,
// C <= 0, bad kernel parameters, bad options, inconsistent warm start). With a workspace, a warm
// start from the workspace's last solve keeps its cached kernel columns (svm/solver_workspace.hpp);
// the result is the same optimum either way. With `shared` (built from X and kernel), the kernel
// columns come from there (svm/shared_columns.hpp): problems over the same samples compute each
// column once between them.
SolverResult solveBinary(const Eigen::MatrixXd& X, const Eigen::VectorXd& y,
                         const Eigen::VectorXd& C, const Kernel& kernel, const SolverOptions& opt,
                         const WarmStart* warm = nullptr, SolverWorkspace* workspace = nullptr,
                         SharedColumns* shared = nullptr);

// Warm start for a new problem from the previous problem (X, y, C, kernel) and its solution.
// previous_index[i] is the previous index of new sample i, or -1 for an added sample.
WarmStart makeWarmStart(const Eigen::MatrixXd& X, const Eigen::VectorXd& y,
                        const Eigen::VectorXd& C, const Kernel& kernel, const SolverResult& previous,
                        std::vector<Eigen::Index> previous_index);

}  // namespace svmp::svm
