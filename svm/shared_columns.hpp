// Kernel columns of one sample set, each computed once, on its first request, and shared by every
// SMO solve over those samples. The one-versus-rest problems of SVMP (svm/one_vs_rest.hpp) differ
// only in labels and C, so each solve computed the same columns again: on panda_shelf 8 solves of
// 1,300 samples computed about 1,000 columns each. A solve given SharedColumns reads its columns in
// place while its samples keep their own order (no shrinking), else gathers them in its shrinking
// order into its cache; it computes none itself.
//
// A column is computed whole, in sample order, by the loop a solve uses (svm/kernel_column.hpp), so
// every entry has one value whichever solve or thread asked first: results do not depend on the
// thread count or the order the solves ran in. Memory: up to n^2 floats, taken as columns are
// first used; fits() keeps that within a column cache's budget.
// Thread safety: column() may be called concurrently; a thread asking for a column another thread
// is computing waits for it (about a microsecond), and computes it itself if that one threw.
#pragma once

#include <Eigen/Core>
#include <atomic>
#include <memory>

#include "svm/kernel.hpp"
#include "svm/kernel_column.hpp"

namespace svmp::svm {

class SharedColumns {
 public:
  SharedColumns(const Eigen::MatrixXd& X, const Kernel& kernel);
  // Whether n samples' columns fit in size_mb (float entries).
  static bool fits(Eigen::Index n, double size_mb);

  int size() const { return samples_.size(); }
  // k(x_s, x_t) for every sample t, in sample order.
  const float* column(int s);
  // True when built from exactly these samples and this kernel.
  bool matches(const Eigen::MatrixXd& X, const Kernel& kernel) const;
  long long computedColumns() const { return computed_.load(std::memory_order_relaxed); }

 private:
  enum State : unsigned char { kEmpty, kComputing, kReady };
  KernelColumns samples_;  // the samples, also what matches() compares with
  struct Free {
    void operator()(float* p) const;
  };
  std::unique_ptr<float[], Free> data_;  // column s at s * n; uninitialised until computed
  std::unique_ptr<std::atomic<unsigned char>[]> state_;
  std::atomic<long long> computed_{0};
};

}  // namespace svmp::svm
