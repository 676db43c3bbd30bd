#include "svm/shared_columns.hpp"

#include <sys/mman.h>

#include <algorithm>
#include <cstdlib>
#include <new>
#include <thread>

namespace svmp::svm {
namespace {

// n^2 floats, in 2 MB pages where the kernel allows (Linux transparent huge pages on madvise) once
// they fill an eighth of one: each first touch of a 4 kB page is a page fault, and in a virtual
// machine a fault costs microseconds (with 4 kB pages, sharing made tunnel3d_zigzag_02's training
// 2.7x slower: 45 MB, 6,600 faults; Fig 4.4's 1.9 MB, 460 faults, made a process's first training
// 12.9 ms against 8.5 ms in one huge page). Smaller sets take 4 kB pages: a huge page is zeroed whole
// at its first touch.
float* allocateColumns(size_t floats) {
  constexpr size_t kHuge = size_t{2} << 20;
  const size_t bytes = std::max<size_t>(floats, 1) * sizeof(float);
  if (bytes < kHuge / 8) {
    void* p = std::malloc(bytes);
    if (p == nullptr) throw std::bad_alloc();
    return static_cast<float*>(p);
  }
  const size_t whole_pages = (bytes + kHuge - 1) / kHuge * kHuge;
  void* p = std::aligned_alloc(kHuge, whole_pages);
  if (p == nullptr) throw std::bad_alloc();
  madvise(p, whole_pages, MADV_HUGEPAGE);  // a hint only
  return static_cast<float*>(p);
}

}  // namespace

void SharedColumns::Free::operator()(float* p) const { std::free(p); }

SharedColumns::SharedColumns(const Eigen::MatrixXd& X, const Kernel& kernel)
    : samples_(X, kernel),
      data_(allocateColumns(static_cast<size_t>(X.cols()) * static_cast<size_t>(X.cols()))),
      state_(new std::atomic<unsigned char>[static_cast<size_t>(X.cols())]) {
  for (Eigen::Index s = 0; s < X.cols(); ++s) state_[s].store(kEmpty, std::memory_order_relaxed);
}

bool SharedColumns::fits(Eigen::Index n, double size_mb) {
  return static_cast<double>(n) * static_cast<double>(n) * sizeof(float) <= size_mb * 1024 * 1024;
}

const float* SharedColumns::column(int s) {
  const int n = samples_.size();
  float* col = data_.get() + static_cast<size_t>(s) * n;
  // A thread whose computation throws (an allocation) leaves the column empty again, so the threads
  // waiting for it take it over rather than wait for ever.
  for (;;) {
    unsigned char expected = kEmpty;
    if (state_[s].compare_exchange_strong(expected, kComputing, std::memory_order_acquire)) {
      try {
        samples_.column(s, 0, n, col);
      } catch (...) {
        state_[s].store(kEmpty, std::memory_order_release);
        throw;
      }
      computed_.fetch_add(1, std::memory_order_relaxed);
      state_[s].store(kReady, std::memory_order_release);
      return col;
    }
    if (expected == kReady) return col;
    std::this_thread::yield();
  }
}

bool SharedColumns::matches(const Eigen::MatrixXd& X, const Kernel& kernel) const {
  if (X.rows() != samples_.dim() || X.cols() != samples_.size() || !(kernel == samples_.kernel())) return false;
  for (int i = 0; i < samples_.size(); ++i)
    for (int k = 0; k < samples_.dim(); ++k)
      if (X(k, i) != samples_.coordinate(k, i)) return false;
  return true;
}

}  // namespace svmp::svm
