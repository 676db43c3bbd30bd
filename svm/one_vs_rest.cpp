#include "svm/one_vs_rest.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <omp.h>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>

#include "svm/shared_columns.hpp"

namespace svmp::svm {

void oneVsRestProblem(const std::vector<int>& labels, int positive_class, double C,
                      const std::map<int, double>& class_weight, Eigen::VectorXd& y,
                      Eigen::VectorXd& sample_C) {
  const Eigen::Index n = static_cast<Eigen::Index>(labels.size());
  y.resize(n);
  sample_C.resize(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    y[i] = labels[i] == positive_class ? 1.0 : -1.0;
    const auto w = class_weight.find(labels[i]);
    sample_C[i] = C * (w == class_weight.end() ? 1.0 : w->second);
  }
}

std::vector<int> oneVsRestClasses(const Eigen::MatrixXd& X, const std::vector<int>& labels, double C,
                                  const std::map<int, double>& class_weight, int threads, const char* who) {
  std::ostringstream msg;
  msg << who << ": ";
  if (static_cast<Eigen::Index>(labels.size()) != X.cols()) {
    msg << labels.size() << " labels for " << X.cols() << " samples";
    throw std::invalid_argument(msg.str());
  }
  if (!(C > 0.0) || !std::isfinite(C)) {
    msg << "C must be positive and finite, got " << C;
    throw std::invalid_argument(msg.str());
  }
  for (const auto& [label, w] : class_weight) {
    if (!(w > 0.0) || !std::isfinite(w)) {
      msg << "weight of class " << label << " must be positive, got " << w;
      throw std::invalid_argument(msg.str());
    }
  }
  if (threads < 1) {
    msg << "threads must be >= 1";
    throw std::invalid_argument(msg.str());
  }
  const std::set<int> distinct(labels.begin(), labels.end());
  if (distinct.size() < 2) {
    msg << "need at least 2 classes, got " << distinct.size();
    throw std::invalid_argument(msg.str());
  }
  return {distinct.begin(), distinct.end()};
}

namespace {

// Whether the problems after the first share their kernel columns, solving without shrinking
// (svm/shared_columns.hpp), judged from the first problem's solve: each of the k - 1 others would
// compute about as many kernel entries as it did; shared, they compute at most the whole matrix
// (n^2 entries), but their loops run over every sample instead of the active ones. A loop entry
// (working-set selection and gradient update, per iteration) costs about half a kernel entry
// (panda_shelf's profile: 0.39 against 0.81 percent of the time per million).
bool shareColumns(const SolverResult& first, Eigen::Index n, int k, const SolverOptions& opt) {
  if (k < 2 || !SharedColumns::fits(n, opt.cache_mb)) return false;
  const double rest = k - 1, samples = static_cast<double>(n);
  const double saved = rest * static_cast<double>(first.kernel_entries);
  const double lost = samples * samples + rest * static_cast<double>(first.iterations) * (samples - first.mean_active) / 2;
  return saved > lost;
}

// Whether the first problem's support vectors are few enough for the others to shrink from the
// start, with caches of their own, instead of sharing columns without shrinking. forest_200's colour
// models keep 10% of 673 samples as support vectors; their loops over every sample were most of
// the training. Where half the samples or more are support vectors (the thesis' arms, panda_shelf),
// early shrinks are undone by gradient reconstructions (docs/dev-log.md, twelfth session).
bool sparseSupport(const SolverResult& first, Eigen::Index n) {
  constexpr double kSparse = 0.25;
  return first.support_vectors < kSparse * static_cast<double>(n);
}

}  // namespace

OneVsRestModel trainOneVsRest(const Eigen::MatrixXd& X, const std::vector<int>& labels,
                              const Kernel& kernel, double C,
                              const std::map<int, double>& class_weight, const SolverOptions& opt,
                              int threads) {
  const std::vector<int> classes = oneVsRestClasses(X, labels, C, class_weight, threads, "trainOneVsRest");
  OneVsRestModel out;
  out.classes = classes;
  const int k = static_cast<int>(out.classes.size());
  out.models.resize(k);
  out.solutions.resize(k);
  const int workers = std::min(threads, k);
  std::vector<std::exception_ptr> errors(k);
  // One workspace per thread: a thread's next class reuses its column cache's memory.
  std::vector<SolverWorkspace> workspaces(workers);
  auto solve = [&](int c, SolverWorkspace& workspace, const SolverOptions& options, SharedColumns* shared) {
    try {
      Eigen::VectorXd y, sample_C;
      oneVsRestProblem(labels, out.classes[c], C, class_weight, y, sample_C);
      if (options.stop && options.stop()) {  // past the limit: the classes left stay untrained (alpha 0)
        out.solutions[c].alpha = Eigen::VectorXd::Zero(X.cols());
        out.solutions[c].status = SolverStatus::kStopped;
      } else {
        out.solutions[c] = solveBinary(X, y, sample_C, kernel, options, nullptr, &workspace, shared);
      }
      out.solutions[c].workspace_solve = 0;  // the workspaces end here
      out.models[c] = BinaryModel::fromSolution(X, y, out.solutions[c], kernel);
    } catch (...) {
      errors[c] = std::current_exception();
    }
  };
  // The first problem alone, with a cache of its own; from its solve, whether the rest share columns.
  solve(0, workspaces[0], opt, nullptr);
  if (errors[0]) std::rethrow_exception(errors[0]);
  std::optional<SharedColumns> shared;
  SolverOptions rest = opt;
  if (sparseSupport(out.solutions[0], X.cols())) {
    rest.early_shrinking = rest.shrinking;
  } else if (shareColumns(out.solutions[0], X.cols(), k, opt)) {
    shared.emplace(X, kernel);
    rest.shrinking = false;  // so the columns stay in sample order, read in place
  }
#pragma omp parallel for num_threads(workers) schedule(dynamic, 1)
  for (int c = 1; c < k; ++c) solve(c, workspaces[omp_get_thread_num()], rest, shared ? &*shared : nullptr);
  for (auto& e : errors)
    if (e) std::rethrow_exception(e);
  out.shared_columns = shared ? shared->computedColumns() : 0;
  out.early_shrinking = rest.early_shrinking;
  return out;
}

}  // namespace svmp::svm
