// Warm start of SMO after samples were added, removed or moved.
//
// The previous dual solution is mapped onto the new samples and made feasible (0 <= alpha_i <= C_i,
// sum_i y_i alpha_i = 0 restored by lowering the largest multipliers of the class in excess); the
// gradient G = Q alpha - e and the bound part G_bar = sum_{alpha_j = C_j} C_j Q_j (libsvm's
// shrinking bookkeeping, Chang & Lin 2011 sec. 5.1) are updated incrementally: one kernel column
// per multiplier that changed (removed, moved or adjusted sample with alpha > 0), and one row over
// the support vectors for each moved or added sample. SMO then converges to the same optimum as a
// cold start (the dual of thesis eq. 2.10 is convex), in far fewer iterations.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "svm/kernel.hpp"
#include "svm/kernel_column.hpp"

namespace svmp::svm {

struct WarmStart {
  // The previous problem and its solution (SolverResult::alpha, gradient, gradient_bound).
  Eigen::MatrixXd X;
  Eigen::VectorXd y;
  Eigen::VectorXd C;
  Eigen::VectorXd alpha;
  Eigen::VectorXd gradient;
  Eigen::VectorXd gradient_bound;
  // The previous problem's kernel: its gradient holds for that kernel only (a start from another
  // one ended "optimal" far from the optimum).
  Kernel kernel;
  // One entry per NEW sample: the index of the previous sample it continues, or -1 if it is new.
  // A continued sample whose coordinates differ is "moved"; previous samples nobody continues are
  // "removed". Coordinates are compared exactly, so callers need not list moved samples.
  std::vector<Eigen::Index> previous_index;
  // SolverResult::workspace_solve of the previous solution: a workspace whose last solve it is
  // keeps its kernel columns for this one.
  long long workspace_solve = 0;

  // "" when consistent with a new problem of n samples in dimension d with `kernel`, else what is
  // wrong: sizes and indices, and values no solve gives (labels not +-1, multipliers outside
  // [0, C], anything not finite), which the solver would take as a start and end "optimal" from.
  std::string validate(Eigen::Index n, Eigen::Index d, const Kernel& new_kernel) const;
};

struct WarmStartCounts {
  long kept = 0, moved = 0, added = 0, removed = 0, adjusted = 0, columns = 0;
  long long reused_columns = 0, patched_rows = 0;  // cached columns carried over by a workspace
};

namespace detail {
// Feasible start for the new problem (y, C, kernel data in original order): alpha, G, G_bar.
WarmStartCounts initialiseFromWarmStart(const WarmStart& warm, const Eigen::MatrixXd& X,
                                        const Eigen::VectorXd& y, const Eigen::VectorXd& C,
                                        const KernelColumns& data, Eigen::VectorXd& alpha,
                                        Eigen::VectorXd& G, Eigen::VectorXd& G_bar);
}  // namespace detail

}  // namespace svmp::svm
