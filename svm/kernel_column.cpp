#include "svm/kernel_column.hpp"

#include "svm/simd_loops.hpp"

#include <algorithm>
#include <utility>

namespace svmp::svm {

namespace {
constexpr int kParallelMin = 8192;
}  // namespace

KernelColumns::KernelColumns(const Eigen::MatrixXd& X, const Kernel& kernel, int threads)
    : n_(static_cast<int>(X.cols())),
      d_(static_cast<int>(X.rows())),
      kernel_(kernel),
      threads_(std::max(1, threads)),
      coords_(static_cast<size_t>(X.rows()) * X.cols()),
      diag_(X.cols()) {
  for (int i = 0; i < n_; ++i)
    for (int k = 0; k < d_; ++k) coords_[static_cast<size_t>(k) * n_ + i] = X(k, i);
  for (int i = 0; i < n_; ++i) diag_[i] = kernel_.value(X.col(i).data(), X.col(i).data(), d_);
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

template <typename Out>
void KernelColumns::computeRange(const double* z, int begin, int end, Out* out) const {
  const int len = end - begin;
  if (threads_ > 1 && len >= kParallelMin) {
    const int parts = threads_;
#pragma omp parallel for num_threads(parts) schedule(static)
    for (int p = 0; p < parts; ++p) {
      const int b = begin + static_cast<int>(static_cast<long>(len) * p / parts);
      const int e = begin + static_cast<int>(static_cast<long>(len) * (p + 1) / parts);
      computeBlock(z, b, e, out + (b - begin));
    }
    return;
  }
  computeBlock(z, begin, end, out);
}

void KernelColumns::compute(const double* z, int begin, int end, float* out) const {
  computeRange(z, begin, end, out);
}

void KernelColumns::compute(const double* z, int begin, int end, double* out) const {
  computeRange(z, begin, end, out);
}

void KernelColumns::column(int i, int begin, int end, float* out) const {
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
