#include "svm/local_one_vs_rest.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <nanoflann.hpp>
#include <stdexcept>

#include "svm/column_cloud.hpp"
#include "svm/box_loops.hpp"
#include "svm/simd_loops.hpp"

namespace svmp::svm {
namespace {

using KdTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, ColumnCloud>, ColumnCloud,
                                                   -1, size_t>;

// Search result set that stops at the first sample closer than the radius (squared).
struct AnyWithin {
  double radius;
  bool found = false;
  size_t size() const { return 0; }
  bool full() const { return true; }
  double worstDist() const { return radius; }
  bool addPoint(double, size_t) {
    found = true;
    return false;
  }
};

// Greedy coordinate descent on min 1/2 a'Qa - p'a, 0 <= a <= C, Q_ij = y_i y_j K_ij with the kernel
// truncated below exp(-5); one sample per column of `samples`.
// Over-relaxed (projected SOR): a step goes kOverRelaxation times the distance to the coordinate's
// own minimum (Q_ii = 1), clipped to the box. Any factor in (0, 2) still lowers the objective at
// every step, and the stop is the same KKT violation. Neighbouring samples' coordinates are strongly
// coupled (samples a step apart, sigma twice the step), and full steps zig-zag between them: over
// 10-20 seeds, 1.5 took 0.45-0.52x the iterations of plain steps on Figs 2.10, 4.4, 4.10 and
// panda_shelf (1.3: 0.59-0.61x, 1.7: 0.50-0.64x, 1.9: 1.4x on Fig 4.10), same objective.
constexpr double kOverRelaxation = 1.5;
SolverResult solveFixedBias(const Eigen::MatrixXd& samples, const Eigen::VectorXd& y, const Eigen::VectorXd& C,
                            double gamma, double bias, const SolverOptions& opt) {
  const int m = static_cast<int>(y.size()), d = static_cast<int>(samples.rows());
  // Row-major copy: rbfColumn reads coordinate c of sample t at X[c * m + t].
  const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> X = samples;
  const float cut = static_cast<float>(std::exp(-5.0));
  SolverResult r;
  r.alpha = Eigen::VectorXd::Zero(m);
  r.bias = bias;
  const Eigen::VectorXd p = (1.0 - bias * y.array()).matrix();
  // G = Qa - p; up[t] opens a growing step while a_t < C_t and down[t] a shrinking one while a_t > 0
  // (svm/box_loops.hpp): the largest violation's index is t to grow a_t, m + t to shrink it.
  constexpr double kClosed = -std::numeric_limits<double>::infinity();
  std::vector<double> G(m), up(m), down(m, kClosed);
  for (int t = 0; t < m; ++t) {
    G[t] = -p[t];
    up[t] = C[t] > 0 ? 0.0 : kClosed;
  }
  std::vector<std::vector<float>> columns(m);
  std::vector<double> z(d);
  auto column = [&](int i) -> const float* {  // y_t K_ti, truncated below exp(-5)
    std::vector<float>& k = columns[i];
    if (k.empty()) {
      k.resize(m);
      for (int c = 0; c < d; ++c) z[c] = X(c, i);
      loops::rbfColumn(X.data(), m, d, z.data(), -gamma, m, k.data());
      for (int t = 0; t < m; ++t) k[t] = k[t] < cut ? 0.0f : static_cast<float>(y[t]) * k[t];
      ++r.cache_misses;
      r.kernel_entries += m;
    } else {
      ++r.cache_hits;
    }
    return k.data();
  };
  loops::ArgMax worst = loops::updateGradientSelectBox(m, G.data(), nullptr, 0.0, up.data(), down.data());
  while (worst.index >= 0 && worst.value > opt.eps) {
    if (r.iterations >= opt.max_iterations) {
      r.status = SolverStatus::kIterationLimit;
      break;
    }
    if (opt.stop && r.iterations % 1000 == 0 && r.iterations > 0 && opt.stop()) {
      r.status = SolverStatus::kStopped;
      break;
    }
    ++r.iterations;
    const int i = worst.index % m;
    const double next = std::clamp(r.alpha[i] - kOverRelaxation * G[i], 0.0, C[i]);
    const double w = (next - r.alpha[i]) * y[i];
    r.alpha[i] = next;
    up[i] = next < C[i] ? 0.0 : kClosed;
    down[i] = next > 0 ? 0.0 : kClosed;
    worst = loops::updateGradientSelectBox(m, G.data(), column(i), w, up.data(), down.data());
  }
  r.violation = worst.index >= 0 ? std::max(0.0, worst.value) : 0.0;
  r.gradient = Eigen::Map<const Eigen::VectorXd>(G.data(), m);
  r.objective = 0.5 * r.alpha.dot(r.gradient + p) - p.dot(r.alpha);
  for (int i = 0; i < m; ++i) {
    r.support_vectors += r.alpha[i] > 0;
    r.bounded_support_vectors += r.alpha[i] > 0 && r.alpha[i] >= C[i];
  }
  r.mean_active = m;
  return r;
}

}  // namespace

// Per class, a k-d tree over its own samples, asked of every other sample whether one lies within
// the radius; the search stops at the first, and a sample beyond the radius of the class's bounding
// box is not searched. A radius search around each of the class's own samples met every neighbour
// again from each of them: 3.2x the time on Fig 4.10's boundary samples (BM_ClassNeighbourhoods).
std::vector<std::vector<int>> classNeighbourhoods(const Eigen::MatrixXd& X, const std::vector<int>& labels,
                                                  const std::vector<int>& classes, const Kernel& kernel,
                                                  double max_share) {
  if (!kernel.isPlainRbf()) throw std::invalid_argument("classNeighbourhoods: needs the plain RBF kernel");
  const double radius2 = 5.0 / kernel.gamma;  // exp(-gamma d^2) >= exp(-5)
  const int k = static_cast<int>(classes.size());
  const Eigen::Index n = X.cols();
  std::vector<std::vector<int>> out(k);
  const double max_entries = max_share * k * static_cast<double>(n) * static_cast<double>(n);
  double entries = 0;
  for (int c = 0; c < k; ++c) {
    std::vector<Eigen::Index> own;
    for (Eigen::Index i = 0; i < n; ++i)
      if (labels[i] == classes[c]) own.push_back(i);
    if (own.empty()) continue;
    Eigen::MatrixXd members(X.rows(), static_cast<Eigen::Index>(own.size()));
    for (size_t j = 0; j < own.size(); ++j) members.col(static_cast<Eigen::Index>(j)) = X.col(own[j]);
    const Eigen::VectorXd lo = members.rowwise().minCoeff(), hi = members.rowwise().maxCoeff();
    const ColumnCloud cloud{&members};
    const KdTree tree(static_cast<int>(X.rows()), cloud, nanoflann::KDTreeSingleIndexAdaptorParams(16));
    for (Eigen::Index i = 0; i < n; ++i) {
      bool near = labels[i] == classes[c];
      if (!near && (X.col(i).cwiseMax(lo).cwiseMin(hi) - X.col(i)).squaredNorm() < radius2) {
        AnyWithin found{radius2};
        tree.findNeighbors(found, X.col(i).data(), nanoflann::SearchParams(32, 0.0f, false));
        near = found.found;
      }
      if (near) out[c].push_back(static_cast<int>(i));
    }
    entries += static_cast<double>(out[c].size()) * static_cast<double>(out[c].size());
    if (entries > max_entries) return {};
  }
  return out;
}

double neighbourhoodShare(const std::vector<std::vector<int>>& neighbourhoods, Eigen::Index n) {
  if (neighbourhoods.empty() || n == 0) return 1.0;
  double entries = 0;
  for (const auto& h : neighbourhoods) entries += static_cast<double>(h.size()) * static_cast<double>(h.size());
  return entries / (static_cast<double>(neighbourhoods.size()) * static_cast<double>(n) * static_cast<double>(n));
}

OneVsRestModel trainOneVsRestLocal(const Eigen::MatrixXd& X, const std::vector<int>& labels,
                                   const Kernel& kernel, double C,
                                   const std::map<int, double>& class_weight, const SolverOptions& opt,
                                   int threads, const std::vector<std::vector<int>>* neighbourhoods) {
  OneVsRestModel out;
  out.classes = oneVsRestClasses(X, labels, C, class_weight, threads, "trainOneVsRestLocal");
  if (!kernel.isPlainRbf()) throw std::invalid_argument("trainOneVsRestLocal: needs the plain RBF kernel");
  const int k = static_cast<int>(out.classes.size());
  const std::vector<std::vector<int>> own =
      neighbourhoods ? std::vector<std::vector<int>>{} : classNeighbourhoods(X, labels, out.classes, kernel);
  const std::vector<std::vector<int>>& hoods = neighbourhoods ? *neighbourhoods : own;
  if (static_cast<int>(hoods.size()) != k)
    throw std::invalid_argument("trainOneVsRestLocal: one neighbourhood per class needed");
  out.models.resize(k);
  out.solutions.resize(k);
  const int d = static_cast<int>(X.rows());
  std::vector<std::exception_ptr> errors(k);
#pragma omp parallel for num_threads(std::min(threads, k)) schedule(dynamic, 1)
  for (int c = 0; c < k; ++c) {
    try {
      const std::vector<int>& keep = hoods[c];
      Eigen::VectorXd y_all, C_all;
      oneVsRestProblem(labels, out.classes[c], C, class_weight, y_all, C_all);
      const int m = static_cast<int>(keep.size());
      Eigen::MatrixXd local(d, m);
      Eigen::VectorXd y(m), sample_C(m);
      for (int t = 0; t < m; ++t) local.col(t) = X.col(keep[t]), y[t] = y_all[keep[t]], sample_C[t] = C_all[keep[t]];
      SolverResult solved;
      if (opt.stop && opt.stop()) {  // past the limit: the classes left stay untrained (alpha 0)
        solved.alpha = Eigen::VectorXd::Zero(m);
        solved.bias = kLocalBias;
        solved.status = SolverStatus::kStopped;
      } else {
        solved = solveFixedBias(local, y, sample_C, kernel.gamma, kLocalBias, opt);
      }
      out.models[c] = BinaryModel::fromSolution(local, y, solved, kernel);
      SolverResult& s = out.solutions[c];
      s = solved;
      s.alpha = Eigen::VectorXd::Zero(X.cols());
      for (int t = 0; t < m; ++t) s.alpha[keep[t]] = solved.alpha[t];
      s.gradient.resize(0);
    } catch (...) {
      errors[c] = std::current_exception();
    }
  }
  for (auto& e : errors)
    if (e) std::rethrow_exception(e);
  return out;
}

}  // namespace svmp::svm
