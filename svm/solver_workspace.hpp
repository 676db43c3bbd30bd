// What a caller keeps between SMO solves of related problems (retraining after samples moved, were
// added or removed): the kernel column cache and the sample order it is in.
//
// A warm start (svm/warm_start.hpp) from the solve this workspace last ran reuses every cached
// column of a kept sample: kept samples stay at the positions they ended at, so only the rows of
// moved, added or relabelled samples are recomputed (the "kernel cache across retrains" of libsvm's
// incremental variants; Chang & Lin 2011 sec. 5.1 for the cache itself). Any other solve reuses the
// cache's memory only. One workspace per thread; not thread-safe.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "svm/kernel.hpp"

namespace svmp::svm {

class KernelCache;
struct WarmStart;

class SolverWorkspace {
 public:
  SolverWorkspace();
  ~SolverWorkspace();
  SolverWorkspace(SolverWorkspace&&) noexcept;
  SolverWorkspace& operator=(SolverWorkspace&&) noexcept;

  // Id of the last solve run in this workspace (0: none); SolverResult::workspace_solve.
  long long lastSolve() const { return last_solve_; }

 private:
  friend struct WorkspaceAccess;
  std::unique_ptr<KernelCache> cache_;
  Kernel kernel_;
  int dim_ = 0;
  double cache_mb_ = 0;
  std::vector<int> order_;  // sample (index in the last problem) at each cache position
  long long last_solve_ = 0;
};

struct RetainedLayout {
  std::vector<int> order;  // new sample at each position
  long long reused_columns = 0, patched_rows = 0;
};

// Internal to the solver (svm/smo_solver.cpp).
struct WorkspaceAccess {
  // The cache for a new problem, laid out as `order`: carried over from the last solve when `warm`
  // continues it with the same kernel, dimension and cache size, else emptied (memory kept).
  static std::unique_ptr<KernelCache> take(SolverWorkspace& w, const Eigen::MatrixXd& X,
                                           const Eigen::VectorXd& y, const Kernel& kernel,
                                           double cache_mb, const WarmStart* warm,
                                           RetainedLayout& layout);
  // Hands the cache back after a solve that ended with `order`; returns the solve's id.
  static long long give(SolverWorkspace& w, std::unique_ptr<KernelCache> cache,
                        const Kernel& kernel, int dim, double cache_mb, std::vector<int> order);
};

}  // namespace svmp::svm
