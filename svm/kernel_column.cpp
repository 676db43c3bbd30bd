#include "svm/kernel_column.hpp"

#include "svm/shared_columns.hpp"
#include "svm/simd_loops.hpp"

#include <algorithm>
#include <utility>

namespace svmp::svm {

std::vector<int> identityOrder(Eigen::Index n) {
  std::vector<int> order(n);
  for (Eigen::Index i = 0; i < n; ++i) order[i] = static_cast<int>(i);
  return order;
}

KernelColumns::KernelColumns(const Eigen::MatrixXd& X, const Kernel& kernel)
    : KernelColumns(X, kernel, identityOrder(X.cols())) {}

KernelColumns::KernelColumns(const Eigen::MatrixXd& X, const Kernel& kernel,
                             const std::vector<int>& order, SharedColumns* shared)
    : n_(static_cast<int>(X.cols())),
      d_(static_cast<int>(X.rows())),
      kernel_(kernel),
      coords_(static_cast<size_t>(X.rows()) * X.cols()),
      diag_(X.cols()),
      shared_(shared) {
  if (shared_) {
    sample_ = order;
    in_order_ = std::is_sorted(order.begin(), order.end());
  }
  for (int t = 0; t < n_; ++t) {
    const double* x = X.col(order[t]).data();
    for (int k = 0; k < d_; ++k) coords_[static_cast<size_t>(k) * n_ + t] = x[k];
    diag_[t] = kernel_.value(x, x, d_);
  }
}

void KernelColumns::point(int i, double* z) const {
  for (int k = 0; k < d_; ++k) z[k] = coords_[static_cast<size_t>(k) * n_ + i];
}

void KernelColumns::swap(int i, int j) {
  if (i == j) return;
  for (int k = 0; k < d_; ++k) {
    double* row = coords_.data() + static_cast<size_t>(k) * n_;
    std::swap(row[i], row[j]);
  }
  std::swap(diag_[i], diag_[j]);
  if (shared_) {
    std::swap(sample_[i], sample_[j]);
    in_order_ = false;
  }
}

template <typename Out>
void KernelColumns::computeBlock(const double* z, int begin, int end, Out* out) const {
  if (kernel_.isPlainRbf()) {
    loops::rbfColumn(coords_.data() + begin, n_, d_, z, -kernel_.gamma, end - begin, out);
    return;
  }
  // Generic kernels: gather each sample (d is small); not a hot path in this project.
  std::vector<double> x(d_);
  for (int t = begin; t < end; ++t) {
    for (int k = 0; k < d_; ++k) x[k] = coords_[static_cast<size_t>(k) * n_ + t];
    out[t - begin] = static_cast<Out>(kernel_.value(z, x.data(), d_));
  }
}

// Single-threaded on purpose: an OpenMP region per column (10-20 us of work at n = 10,000) made
// training 10-100x slower on a loaded 2-core machine; one-versus-rest parallelises over classes.
template <typename Out>
void KernelColumns::computeRange(const double* z, int begin, int end, Out* out) const {
  computeBlock(z, begin, end, out);
}

void KernelColumns::compute(const double* z, int begin, int end, float* out) const {
  computeRange(z, begin, end, out);
}

void KernelColumns::compute(const double* z, int begin, int end, double* out) const {
  computeRange(z, begin, end, out);
}

const float* KernelColumns::inPlace(int i) const {
  return in_order_ ? shared_->column(i) : nullptr;
}

void KernelColumns::column(int i, int begin, int end, float* out) const {
  if (shared_) {
    const float* all = shared_->column(sample_[i]);
    const int* sample = sample_.data();
    for (int t = begin; t < end; ++t) out[t - begin] = all[sample[t]];
    return;
  }
  double z[64];
  std::vector<double> big;
  double* zp = z;
  if (d_ > 64) {
    big.resize(d_);
    zp = big.data();
  }
  point(i, zp);
  computeRange(zp, begin, end, out);
}

}  // namespace svmp::svm
