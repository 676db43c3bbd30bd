// Kernel columns over a dense sample set: k(z, x_t) for a range of samples t.
//
// The hot path of SMO (thesis eq. 2.10 solved as in Fan, Chen, Lin, JMLR 2005) is computing kernel
// columns. Samples are stored coordinate-major (one contiguous array per coordinate), so for the
// RBF kernel the squared distances of a whole column accumulate with unit-stride vector loads and
// the exponential runs over contiguous memory (expNonPositive vectorises). Distances are formed
// from differences rather than |x|^2 + |z|^2 - 2x'z: in this layout both cost the same and
// differences do not cancel for near points, so no squared norms are needed for RBF; the diagonal
// k(x_i, x_i) is precomputed for every kernel. swap() keeps the storage in the solver's (shrinking)
// order. Given SharedColumns of the same samples (svm/shared_columns.hpp), column() copies from them
// in that order instead of computing.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "svm/kernel.hpp"

namespace svmp::svm {

// 0, 1, ..., n-1: the sample order of a solve that starts afresh.
std::vector<int> identityOrder(Eigen::Index n);

class SharedColumns;

class KernelColumns {
 public:
  KernelColumns(const Eigen::MatrixXd& X, const Kernel& kernel);
  // Sample order[t] of X at position t (a permutation of the columns of X). shared, when given,
  // holds X's columns (SharedColumns::matches) and outlives this.
  KernelColumns(const Eigen::MatrixXd& X, const Kernel& kernel, const std::vector<int>& order,
                SharedColumns* shared = nullptr);

  int size() const { return n_; }
  int dim() const { return d_; }
  const Kernel& kernel() const { return kernel_; }
  double diagonal(int i) const { return diag_[i]; }
  const double* diagonalData() const { return diag_.data(); }
  double coordinate(int k, int i) const { return coords_[static_cast<size_t>(k) * n_ + i]; }
  void point(int i, double* z) const;  // writes the d coordinates of sample i

  // out[t - begin] = k(z, x_t) for t in [begin, end). z has dim() coordinates.
  void compute(const double* z, int begin, int end, float* out) const;
  void compute(const double* z, int begin, int end, double* out) const;
  // Column of sample i (z = x_i).
  void column(int i, int begin, int end, float* out) const;
  // With shared columns while every sample is still at its own position: column i itself, whole,
  // to be read in place (no copy, no cache). Otherwise nullptr.
  const float* inPlace(int i) const;

  void swap(int i, int j);

 private:
  template <typename Out>
  void computeRange(const double* z, int begin, int end, Out* out) const;
  template <typename Out>
  void computeBlock(const double* z, int begin, int end, Out* out) const;

  int n_;
  int d_;
  Kernel kernel_;
  std::vector<double> coords_;  // d x n, row k holds coordinate k of every sample
  std::vector<double> diag_;
  SharedColumns* shared_ = nullptr;
  std::vector<int> sample_;  // with shared_: the sample at each position
  bool in_order_ = false;    // with shared_: sample_[t] == t for every t
};

}  // namespace svmp::svm
