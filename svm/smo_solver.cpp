#include "svm/smo_solver.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "svm/kernel_cache.hpp"
#include "svm/kernel_column.hpp"
#include "svm/shared_columns.hpp"
#include "svm/simd_loops.hpp"
#include "svm/smo_parallel.hpp"
#include "svm/solver_workspace.hpp"

namespace svmp::svm {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kTau = 1e-12;  // libsvm's TAU: curvature used when k_ii + k_jj - 2k_ij <= 0

[[noreturn]] void fail(const std::string& what) {
  throw std::invalid_argument("solveBinary: " + what);
}

void validateProblem(const Eigen::MatrixXd& X, const Eigen::VectorXd& y, const Eigen::VectorXd& C,
                     const Kernel& kernel, const SolverOptions& opt) {
  std::ostringstream msg;
  if (X.cols() == 0) fail("no samples (X has 0 columns)");
  if (X.rows() == 0) fail("samples have dimension 0");
  if (y.size() != X.cols()) {
    msg << "y has " << y.size() << " labels but X has " << X.cols() << " samples";
    fail(msg.str());
  }
  if (C.size() != X.cols()) {
    msg << "C has " << C.size() << " entries but X has " << X.cols() << " samples";
    fail(msg.str());
  }
  if (X.cols() > std::numeric_limits<int>::max() / 2) fail("too many samples");
  if (!X.allFinite()) fail("X contains NaN or Inf");
  bool has_pos = false, has_neg = false;
  for (Eigen::Index i = 0; i < y.size(); ++i) {
    if (y[i] == 1.0)
      has_pos = true;
    else if (y[i] == -1.0)
      has_neg = true;
    else {
      msg << "label y[" << i << "] = " << y[i] << "; labels must be +1 or -1";
      fail(msg.str());
    }
    if (!(C[i] > 0.0) || !std::isfinite(C[i])) {
      msg << "C[" << i << "] = " << C[i] << "; C must be positive and finite";
      fail(msg.str());
    }
  }
  if (!has_neg) fail("labels contain only class +1; need both classes");
  if (!has_pos) fail("labels contain only class -1; need both classes");
  if (const std::string k = kernel.validate(static_cast<int>(X.rows())); !k.empty()) fail(k);
  if (const std::string o = opt.validate(); !o.empty()) fail(o);
}

// Solver state in the shrinking permutation: samples [0, active_) are active.
class SmoSolver {
 public:
  // Sample order[t] at position t; data and cache are laid out the same way.
  SmoSolver(KernelColumns& data, KernelCache& cache, const std::vector<int>& order,
            const Eigen::VectorXd& y, const Eigen::VectorXd& C, const SolverOptions& opt)
      : data_(data),
        opt_(opt),
        n_(data.size()),
        active_(n_),
        cache_(cache),
        y_(n_),
        C_(n_),
        alpha_(n_, 0.0),
        yG_(n_),
        G_bar_(n_, 0.0),
        scratch_(n_),
        up_penalty_(n_),
        low_penalty_(n_),
        index_(order),
        part_max_(std::max(1, opt.threads)),
        part_j_(std::max(1, opt.threads)),
        part_offset_(std::max(1, opt.threads)) {
    for (int t = 0; t < n_; ++t) {
      y_[t] = y[index_[t]];
      C_[t] = C[index_[t]];
      yG_[t] = -y_[t];  // G = Q alpha - e at alpha = 0
    }
  }

  // A warm start has an accurate gradient from the start, so shrinking may begin at once: the
  // kernel columns are then computed over the active set only (libsvm waits 1000 iterations).
  // Vectors in sample order.
  void setStart(const Eigen::VectorXd& alpha, const Eigen::VectorXd& G, const Eigen::VectorXd& Gb) {
    shrink_at_start_ = true;
    for (int t = 0; t < n_; ++t) {
      alpha_[t] = alpha[index_[t]];
      yG_[t] = y_[t] * G[index_[t]];
      G_bar_[t] = Gb[index_[t]];
    }
  }

  SolverResult run();
  const std::vector<int>& order() const { return index_; }

 private:
  bool isUpper(int i) const { return alpha_[i] >= C_[i]; }
  bool isLower(int i) const { return alpha_[i] <= 0.0; }
  bool isFree(int i) const { return !isUpper(i) && !isLower(i); }
  double gradient(int i) const { return y_[i] * yG_[i]; }
  bool inUp(int i) const { return y_[i] > 0 ? !isUpper(i) : !isLower(i); }
  bool inLow(int i) const { return y_[i] > 0 ? !isLower(i) : !isUpper(i); }
  void updateMasks(int i) {
    up_penalty_[i] = inUp(i) ? 0.0 : -kInf;
    low_penalty_[i] = inLow(i) ? 0.0 : kInf;
  }

  const float* column(int i, int len) {
    if (const float* whole = data_.inPlace(i)) return whole;
    int filled = 0;
    float* col = cache_.request(i, len, &filled);
    if (filled < len) {
      parallel::forChunks(len - filled, opt_.threads, opt_.parallel_min_samples,
                          [&](int b, int e, int) {
                            data_.column(i, filled + b, filled + e, col + filled + b);
                          });
      kernel_entries_ += len - filled;
    }
    return col;
  }

  // The loops of simd_loops.hpp over [0, m), in chunks when the solve has threads.
  loops::ArgMax selectI(int m) {
    resetParts();
    parallel::forChunks(m, opt_.threads, opt_.parallel_min_samples, [&](int b, int e, int c) {
      part_offset_[c] = b;
      part_max_[c] = loops::selectI(e - b, up_penalty_.data() + b, yG_.data() + b);
    });
    return parallel::mergeMax(part_max_, part_offset_);
  }
  loops::SelectJ selectJ(int m, const float* Ki, int i, double gmax) {
    resetParts();
    parallel::forChunks(m, opt_.threads, opt_.parallel_min_samples, [&](int b, int e, int c) {
      part_offset_[c] = b;
      part_j_[c] = loops::selectJ(e - b, low_penalty_.data() + b, yG_.data() + b,
                                  data_.diagonalData() + b, Ki + b, data_.diagonal(i), gmax, kTau);
    });
    return parallel::mergeSelectJ(part_j_, part_offset_);
  }
  loops::ArgMax updateGradientSelectI(int m, const float* Ki, const float* Kj, double wi,
                                      double wj) {
    resetParts();
    parallel::forChunks(m, opt_.threads, opt_.parallel_min_samples, [&](int b, int e, int c) {
      part_offset_[c] = b;
      part_max_[c] = loops::updateGradientSelectI(e - b, yG_.data() + b, Ki + b, Kj + b, wi, wj,
                                                  up_penalty_.data() + b);
    });
    return parallel::mergeMax(part_max_, part_offset_);
  }
  void resetParts() {
    std::fill(part_max_.begin(), part_max_.end(), loops::ArgMax{-kInf, -1});
    std::fill(part_j_.begin(), part_j_.end(), loops::SelectJ{-kInf, kInf, -1});
    std::fill(part_offset_.begin(), part_offset_.end(), 0);
  }

  bool selectWorkingSet(int& out_i, int& out_j);
  void update(int i, int j);
  void shrink();
  void reconstructGradient();
  bool beShrunk(int i, double gmax1, double gmax2) const;
  void swapIndex(int i, int j);  // everything but the cache; see shrink()
  double bias() const;
  double violation() const;

  KernelColumns& data_;
  const SolverOptions& opt_;
  int n_;
  int active_;
  long long kernel_entries_ = 0;
  long long active_sum_ = 0;
  loops::ArgMax next_i_{0.0, -1};  // selectI's answer for the current active set, if valid
  bool next_i_valid_ = false;
  bool unshrink_ = false;
  bool shrink_at_start_ = false;
  KernelCache& cache_;
  // y_t G_t rather than G_t (y_t = +-1): the gradient update then needs no labels, and the
  // selection loops read one array less.
  std::vector<double> y_, C_, alpha_, yG_, G_bar_, scratch_;
  // I_up / I_low (Keerthi et al.) as additive penalties: 0 when in the set, -inf / +inf when not.
  std::vector<double> up_penalty_, low_penalty_;
  std::vector<int> index_;  // original index of each position
  std::vector<std::pair<int, int>> swaps_;
  std::vector<loops::ArgMax> part_max_;  // per-chunk results of the threaded loops
  std::vector<loops::SelectJ> part_j_;
  std::vector<int> part_offset_;
};

bool SmoSolver::selectWorkingSet(int& out_i, int& out_j) {
  const int m = active_;
  // i = argmax_{t in I_up} -y_t G_t; masks are additive penalties so the loops are branch-free.
  const loops::ArgMax best_i = next_i_valid_ ? next_i_ : selectI(m);
  next_i_valid_ = false;
  if (best_i.index < 0) return false;
  const int i = best_i.index;
  const double gmax = best_i.value;
  // j = argmin over t in I_low with y_t G_t > -gmax of -(gmax + y_t G_t)^2 / curvature (WSS2)
  const float* Ki = column(i, m);
  const loops::SelectJ best_j = selectJ(m, Ki, i, gmax);
  if (gmax + best_j.gmax2 < opt_.eps || best_j.j < 0) return false;
  const int j = best_j.j;
  out_i = i;
  out_j = j;
  return true;
}

void SmoSolver::update(int i, int j) {
  const float* Ki = column(i, active_);
  const float* Kj = column(j, active_);  // the cache keeps >= 2 columns, so Ki stays valid
  const double Ci = C_[i], Cj = C_[j];
  const double old_ai = alpha_[i], old_aj = alpha_[j];
  const double kij = Ki[j];
  double& ai = alpha_[i];
  double& aj = alpha_[j];
  // Two-variable subproblem, clipped to the box along the constraint line (libsvm's update).
  if (y_[i] != y_[j]) {
    double quad = data_.diagonal(i) + data_.diagonal(j) - 2.0 * kij;
    if (quad <= 0) quad = kTau;
    const double delta = (-gradient(i) - gradient(j)) / quad;
    const double diff = ai - aj;
    ai += delta;
    aj += delta;
    if (diff > 0) {
      if (aj < 0) {
        aj = 0;
        ai = diff;
      }
    } else {
      if (ai < 0) {
        ai = 0;
        aj = -diff;
      }
    }
    if (diff > Ci - Cj) {
      if (ai > Ci) {
        ai = Ci;
        aj = Ci - diff;
      }
    } else {
      if (aj > Cj) {
        aj = Cj;
        ai = Cj + diff;
      }
    }
  } else {
    double quad = data_.diagonal(i) + data_.diagonal(j) - 2.0 * kij;
    if (quad <= 0) quad = kTau;
    const double delta = (gradient(i) - gradient(j)) / quad;
    const double sum = ai + aj;
    ai -= delta;
    aj += delta;
    if (sum > Ci) {
      if (ai > Ci) {
        ai = Ci;
        aj = sum - Ci;
      }
    } else {
      if (aj < 0) {
        aj = 0;
        ai = sum;
      }
    }
    if (sum > Cj) {
      if (aj > Cj) {
        aj = Cj;
        ai = sum - Cj;
      }
    } else {
      if (ai < 0) {
        ai = 0;
        aj = sum;
      }
    }
  }
  // G_t += Q_ti dA_i + Q_tj dA_j with Q_ti = y_t y_i K_ti, so y_t G_t += y_i dA_i K_ti + ...
  const double wi = y_[i] * (ai - old_ai);
  const double wj = y_[j] * (aj - old_aj);
  const bool was_upper_i = old_ai >= Ci, was_upper_j = old_aj >= Cj;
  updateMasks(i);
  updateMasks(j);
  // The next iteration's i comes out of the same pass (valid until shrinking changes the set).
  next_i_ = updateGradientSelectI(active_, Ki, Kj, wi, wj);
  next_i_valid_ = true;
  const double* y = y_.data();
  // G_bar changes when a multiplier enters or leaves its upper bound; needs the full column.
  for (int k : {i, j}) {
    const bool was_upper = (k == i) ? was_upper_i : was_upper_j;
    if (was_upper == isUpper(k)) continue;
    const float* Kk = column(k, n_);
    const double w = (was_upper ? -C_[k] : C_[k]) * y_[k];
    double* Gb = G_bar_.data();
    parallel::forChunks(n_, opt_.threads, opt_.parallel_min_samples, [&](int b, int e, int) {
#pragma omp simd
      for (int t = b; t < e; ++t) Gb[t] += w * y[t] * static_cast<double>(Kk[t]);
    });
  }
}

bool SmoSolver::beShrunk(int i, double gmax1, double gmax2) const {
  const double g = gradient(i);
  if (isUpper(i)) return y_[i] > 0 ? -g > gmax1 : -g > gmax2;
  if (isLower(i)) return y_[i] > 0 ? g > gmax2 : g > gmax1;
  return false;
}

void SmoSolver::shrink() {
  next_i_valid_ = false;
  // gmax1 = max_{I_up} -y G, gmax2 = max_{I_low} y G  (libsvm's do_shrinking)
  double gmax1 = -kInf, gmax2 = -kInf;
  for (int t = 0; t < active_; ++t) {
    const double yg = yG_[t];
    if (inUp(t)) gmax1 = std::max(gmax1, -yg);
    if (inLow(t)) gmax2 = std::max(gmax2, yg);
  }
  if (!unshrink_ && gmax1 + gmax2 <= opt_.eps * 10) {
    unshrink_ = true;
    reconstructGradient();
    active_ = n_;
  }
  swaps_.clear();
  for (int i = 0; i < active_; ++i) {
    if (!beShrunk(i, gmax1, gmax2)) continue;
    --active_;
    while (active_ > i) {
      if (!beShrunk(active_, gmax1, gmax2)) {
        swapIndex(i, active_);
        swaps_.emplace_back(i, active_);
        break;
      }
      --active_;
    }
  }
  cache_.swapIndices(swaps_);
}

void SmoSolver::reconstructGradient() {
  if (active_ == n_) return;
  next_i_valid_ = false;
  for (int t = active_; t < n_; ++t) yG_[t] = y_[t] * (G_bar_[t] - 1.0);
  // w_j = y_j alpha_j for free j (bounded ones are in G_bar already)
  int free_count = 0;
  for (int j = 0; j < active_; ++j) {
    const bool f = isFree(j);
    scratch_[j] = f ? y_[j] * alpha_[j] : 0.0;
    free_count += f;
  }
  const double* w = scratch_.data();
  if (static_cast<double>(free_count) * n_ > 2.0 * active_ * (n_ - active_)) {
    for (int i = active_; i < n_; ++i) {
      const float* Ki = column(i, active_);
      double sum = 0.0;
#pragma omp simd reduction(+ : sum)
      for (int j = 0; j < active_; ++j) sum += w[j] * static_cast<double>(Ki[j]);
      yG_[i] += sum;
    }
  } else {
    for (int i = 0; i < active_; ++i) {
      if (w[i] == 0.0) continue;
      const float* Ki = column(i, n_);
      // y_t G_t += w_i K_it over the inactive part (the two-column update with a zero weight)
      loops::updateGradient(n_ - active_, yG_.data() + active_, Ki + active_, Ki + active_, w[i],
                            0.0);
    }
  }
}

void SmoSolver::swapIndex(int i, int j) {
  if (i == j) return;
  data_.swap(i, j);
  std::swap(y_[i], y_[j]);
  std::swap(C_[i], C_[j]);
  std::swap(alpha_[i], alpha_[j]);
  std::swap(yG_[i], yG_[j]);
  std::swap(G_bar_[i], G_bar_[j]);
  std::swap(up_penalty_[i], up_penalty_[j]);
  std::swap(low_penalty_[i], low_penalty_[j]);
  std::swap(index_[i], index_[j]);
}

double SmoSolver::bias() const {
  // libsvm's calculate_rho: average of y G over free multipliers, else midpoint of the feasible
  // interval; bias = -rho.
  double ub = kInf, lb = -kInf, sum_free = 0.0;
  int nr_free = 0;
  for (int i = 0; i < active_; ++i) {
    const double yg = yG_[i];
    if (isUpper(i)) {
      if (y_[i] < 0)
        ub = std::min(ub, yg);
      else
        lb = std::max(lb, yg);
    } else if (isLower(i)) {
      if (y_[i] > 0)
        ub = std::min(ub, yg);
      else
        lb = std::max(lb, yg);
    } else {
      ++nr_free;
      sum_free += yg;
    }
  }
  const double rho = nr_free > 0 ? sum_free / nr_free : (ub + lb) / 2;
  return -rho;
}

double SmoSolver::violation() const {
  double m_up = -kInf, m_low = -kInf;
  for (int t = 0; t < n_; ++t) {
    const double yg = yG_[t];
    if (inUp(t)) m_up = std::max(m_up, -yg);
    if (inLow(t)) m_low = std::max(m_low, yg);
  }
  return m_up + m_low;
}

SolverResult SmoSolver::run() {
  // libsvm shrinks every 1000 iterations; a warm start often finishes in fewer, so it shrinks every
  // 100 (d = 2: the active set 10,000 -> 3,000 and 17% less time; d = 6: 0-8%; 300 and 30 were
  // worse).
  constexpr int kWarmShrinkEvery = 100;
  for (int i = 0; i < n_; ++i) updateMasks(i);
  SolverResult result;
  long iter = 0;
  long long work_since_poll = 0;
  const bool early = shrink_at_start_ || opt_.early_shrinking;
  int counter = early ? 1 : std::min(n_, 1000) + 1;
  result.status = SolverStatus::kOptimal;
  while (true) {
    if (iter >= opt_.max_iterations) {
      result.status = SolverStatus::kIterationLimit;
      break;
    }
    // Polled every 1,000 iterations, or sooner once they have touched 2^20 gradient entries (about a
    // millisecond): an iteration on 50,000 active samples costs 1,000 on 50.
    if (opt_.stop && (iter % 1000 == 0 || work_since_poll >= (1LL << 20))) {
      work_since_poll = 0;
      if (opt_.stop()) {
        result.status = SolverStatus::kStopped;
        break;
      }
    }
    if (--counter == 0) {
      counter = std::min(n_, early ? kWarmShrinkEvery : 1000);
      if (opt_.shrinking) shrink();
    }
    int i = -1, j = -1;
    if (!selectWorkingSet(i, j)) {
      // Optimal on the active set: check again on all samples.
      reconstructGradient();
      active_ = n_;
      if (!selectWorkingSet(i, j)) break;
      counter = 1;  // shrink at the next iteration
    }
    ++iter;
    work_since_poll += active_;
    active_sum_ += active_;
    update(i, j);
  }
  // A stopped solve skips the gradient's reconstruction, which can cost as much as a pass over every
  // kernel column (0.55 s of a 3 s limit on 3,000 obstacles): its caller is out of time.
  const bool stopped = result.status == SolverStatus::kStopped;
  if (active_ < n_ && !stopped) {
    reconstructGradient();
    active_ = n_;
  }
  result.iterations = iter;
  result.bias = bias();
  result.alpha.resize(n_);
  for (int t = 0; t < n_; ++t) {
    result.alpha[index_[t]] = alpha_[t];
    if (alpha_[t] > 0) ++result.support_vectors;
    if (isUpper(t)) ++result.bounded_support_vectors;
  }
  if (stopped) {
    result.objective = result.violation = std::numeric_limits<double>::quiet_NaN();
  } else {
    result.violation = violation();
    result.gradient.resize(n_);
    result.gradient_bound.resize(n_);
    double v = 0.0;
    for (int t = 0; t < n_; ++t) {
      v += alpha_[t] * (gradient(t) - 1.0);
      result.gradient[index_[t]] = gradient(t);
      result.gradient_bound[index_[t]] = G_bar_[t];
    }
    result.objective = 0.5 * v;
  }
  result.cache_hits = cache_.hits();
  result.cache_misses = cache_.misses();
  result.kernel_entries = kernel_entries_;
  result.mean_active = iter > 0 ? static_cast<double>(active_sum_) / iter : 0.0;
  return result;
}

}  // namespace

std::string SolverOptions::validate() const {
  std::ostringstream msg;
  if (!(eps > 0.0) || !std::isfinite(eps))
    msg << "eps must be positive and finite, got " << eps;
  else if (max_iterations <= 0)
    msg << "max_iterations must be positive, got " << max_iterations;
  else if (!(cache_mb >= 0.0) || !std::isfinite(cache_mb))
    msg << "cache_mb must be >= 0 and finite, got " << cache_mb;
  else if (threads < 1 || threads > 1024)
    msg << "threads must be in [1, 1024], got " << threads;
  else if (parallel_min_samples < 8)
    msg << "parallel_min_samples must be >= 8, got " << parallel_min_samples;
  return msg.str();
}

std::string SolverResult::report() const {
  std::ostringstream msg;
  msg << (status == SolverStatus::kOptimal ? "optimal" : status == SolverStatus::kStopped ? "stopped" : "iteration limit")
      << ", iterations "
      << iterations << ", objective " << objective << ", bias " << bias << ", violation "
      << violation << ", SV " << support_vectors << " (bounded " << bounded_support_vectors
      << "), cache hits " << cache_hits << " misses " << cache_misses << ", kernel entries "
      << kernel_entries;
  return msg.str();
}

SolverResult solveBinary(const Eigen::MatrixXd& X, const Eigen::VectorXd& y,
                         const Eigen::VectorXd& C, const Kernel& kernel, const SolverOptions& opt,
                         const WarmStart* warm, SolverWorkspace* workspace, SharedColumns* shared) {
  validateProblem(X, y, C, kernel, opt);
  if (shared != nullptr && !shared->matches(X, kernel)) fail("shared columns of other samples or another kernel");
  if (warm != nullptr)
    if (const std::string w = warm->validate(X.cols(), X.rows(), kernel); !w.empty()) fail(w);
  RetainedLayout layout;
  std::unique_ptr<KernelCache> cache;
  if (workspace != nullptr) {
    cache = WorkspaceAccess::take(*workspace, X, y, kernel, opt.cache_mb, warm, layout);
  } else {
    cache = std::make_unique<KernelCache>(static_cast<int>(X.cols()), opt.cache_mb);
    layout.order = identityOrder(X.cols());
  }
  KernelColumns data(X, kernel, layout.order, shared);
  SmoSolver solver(data, *cache, layout.order, y, C, opt);
  WarmStartCounts counts;
  if (warm != nullptr) {
    // The start is computed in sample order (its kernel rows need no cache): `data` is in that order
    // unless a workspace carried its layout over.
    std::optional<KernelColumns> in_order;
    if (!std::is_sorted(layout.order.begin(), layout.order.end())) in_order.emplace(X, kernel);
    Eigen::VectorXd alpha, G, G_bar;
    counts = detail::initialiseFromWarmStart(*warm, X, y, C, in_order ? *in_order : data, alpha, G,
                                             G_bar);
    solver.setStart(alpha, G, G_bar);
  }
  SolverResult result = solver.run();
  counts.reused_columns = layout.reused_columns;
  counts.patched_rows = layout.patched_rows;
  result.warm = counts;
  if (workspace != nullptr)
    result.workspace_solve = WorkspaceAccess::give(*workspace, std::move(cache), kernel,
                                                   static_cast<int>(X.rows()), opt.cache_mb,
                                                   solver.order());
  return result;
}

WarmStart makeWarmStart(const Eigen::MatrixXd& X, const Eigen::VectorXd& y,
                        const Eigen::VectorXd& C, const Kernel& kernel, const SolverResult& previous,
                        std::vector<Eigen::Index> previous_index) {
  if (previous.status == SolverStatus::kStopped)
    throw std::invalid_argument("warm start: the previous solve was stopped (it has no gradient)");
  WarmStart w;
  w.X = X;
  w.y = y;
  w.C = C;
  w.alpha = previous.alpha;
  w.gradient = previous.gradient;
  w.gradient_bound = previous.gradient_bound;
  w.kernel = kernel;
  w.previous_index = std::move(previous_index);
  w.workspace_solve = previous.workspace_solve;
  return w;
}

}  // namespace svmp::svm
