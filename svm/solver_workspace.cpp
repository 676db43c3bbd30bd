#include "svm/solver_workspace.hpp"

#include <algorithm>
#include <atomic>

#include "svm/kernel_cache.hpp"
#include "svm/kernel_column.hpp"
#include "svm/warm_start.hpp"

namespace svmp::svm {

SolverWorkspace::SolverWorkspace() = default;
SolverWorkspace::~SolverWorkspace() = default;
SolverWorkspace::SolverWorkspace(SolverWorkspace&&) noexcept = default;
SolverWorkspace& SolverWorkspace::operator=(SolverWorkspace&&) noexcept = default;

namespace {

// Lays the new samples out so that each kept sample (same label, same coordinates) sits where it
// ended in the last solve; the others fill the remaining positions. Drops the columns of the rest
// and recomputes, in every column kept, the rows of the samples that are new at their position.
void carryOver(KernelCache& cache, const std::vector<int>& old_order, const Eigen::MatrixXd& X,
               const Eigen::VectorXd& y, const Kernel& kernel, const WarmStart& warm,
               RetainedLayout& layout) {
  const int n = static_cast<int>(X.cols()), n_old = static_cast<int>(old_order.size());
  std::vector<int> old_position(n_old);
  for (int t = 0; t < n_old; ++t) old_position[old_order[t]] = t;
  std::vector<int> owner(std::max(n, n_old), -1);
  std::vector<int> relocate;  // kept samples whose position is past the new size
  std::vector<char> kept(n, 0);
  for (int i = 0; i < n; ++i) {
    const Eigen::Index p = warm.previous_index[i];
    if (p < 0 || warm.y[p] != y[i] || X.col(i) != warm.X.col(p)) continue;
    kept[i] = 1;
    const int at = old_position[p];
    if (at < n)
      owner[at] = i;
    else
      relocate.push_back(i);
  }
  std::vector<int> open;  // positions < n nobody kept
  for (int t = 0; t < n; ++t)
    if (owner[t] < 0) open.push_back(t);
  std::vector<std::pair<int, int>> swaps;
  size_t next_open = 0;
  for (int i : relocate) {
    const int to = open[next_open++];
    swaps.emplace_back(to, old_position[warm.previous_index[i]]);
    owner[to] = i;
  }
  cache.swapIndices(swaps);
  std::vector<int> fresh_positions;
  for (int i = 0; i < n; ++i) {
    if (kept[i]) continue;
    const int at = open[next_open++];
    owner[at] = i;
    fresh_positions.push_back(at);
  }
  std::sort(fresh_positions.begin(), fresh_positions.end());
  cache.resize(n);
  for (int at : fresh_positions) cache.evictColumn(at);

  // Rows of the fresh samples in every column kept: one short kernel row each.
  Eigen::MatrixXd fresh_X(X.rows(), static_cast<Eigen::Index>(fresh_positions.size()));
  for (size_t f = 0; f < fresh_positions.size(); ++f)
    fresh_X.col(f) = X.col(owner[fresh_positions[f]]);
  std::vector<float> row(fresh_positions.size());
  const KernelColumns fresh(fresh_X, kernel);
  for (int t = 0; t < n; ++t) {
    int len = 0;
    float* column = cache.cached(t, &len);
    if (len == 0) continue;
    ++layout.reused_columns;
    const int rows =
        static_cast<int>(std::lower_bound(fresh_positions.begin(), fresh_positions.end(), len) -
                         fresh_positions.begin());
    if (rows == 0) continue;
    fresh.compute(X.col(owner[t]).data(), 0, rows, row.data());
    for (int r = 0; r < rows; ++r) column[fresh_positions[r]] = row[r];
    layout.patched_rows += rows;
  }
  layout.order.assign(owner.begin(), owner.begin() + n);
}

}  // namespace

std::unique_ptr<KernelCache> WorkspaceAccess::take(SolverWorkspace& w, const Eigen::MatrixXd& X,
                                                   const Eigen::VectorXd& y, const Kernel& kernel,
                                                   double cache_mb, const WarmStart* warm,
                                                   RetainedLayout& layout) {
  const int n = static_cast<int>(X.cols());
  std::unique_ptr<KernelCache> cache = std::move(w.cache_);
  if (!cache || w.cache_mb_ != cache_mb) {
    layout.order = identityOrder(n);
    return std::make_unique<KernelCache>(n, cache_mb);
  }
  const bool continues = warm != nullptr && warm->workspace_solve == w.last_solve_ &&
                         w.last_solve_ != 0 && w.kernel_ == kernel && w.dim_ == X.rows() &&
                         static_cast<Eigen::Index>(w.order_.size()) == warm->X.cols();
  if (continues) {
    carryOver(*cache, w.order_, X, y, kernel, *warm, layout);
  } else {
    cache->clear();
    cache->resize(n);
    layout.order = identityOrder(n);
  }
  return cache;
}

long long WorkspaceAccess::give(SolverWorkspace& w, std::unique_ptr<KernelCache> cache,
                                const Kernel& kernel, int dim, double cache_mb,
                                std::vector<int> order) {
  static std::atomic<long long> solves{0};  // ids unique across workspaces
  w.cache_ = std::move(cache);
  w.kernel_ = kernel;
  w.dim_ = dim;
  w.cache_mb_ = cache_mb;
  w.order_ = std::move(order);
  w.last_solve_ = ++solves;
  return w.last_solve_;
}

}  // namespace svmp::svm
