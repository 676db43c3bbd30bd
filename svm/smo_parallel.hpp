// The O(n) loops of one SMO iteration split across OpenMP threads (SolverOptions::threads), for
// problems large enough that it pays: each thread takes one contiguous chunk (a multiple of 8
// entries, so the vector lanes see the same entries), and the working-set choices are merged by
// value, then smallest index, which is the serial loops' tie rule. Element-wise loops give the same
// bits for any thread count; the argmin of selectJ may break an exact-rounding tie differently
// (same thread count, same result).
#pragma once

#include <omp.h>

#include <algorithm>
#include <exception>
#include <vector>

#include "svm/simd_loops.hpp"

namespace svmp::svm::parallel {

// f(begin, end, chunk) for the chunks of [0, m); serial (one chunk) below min_size or with 1
// thread. An exception thrown in a chunk (a kernel column's allocation) is rethrown after the
// region, the lowest chunk's first: one leaving an OpenMP region ends the program.
template <class F>
void forChunks(int m, int threads, int min_size, F&& f) {
  if (threads <= 1 || m < min_size) {
    f(0, m, 0);
    return;
  }
  std::exception_ptr error;  // the lowest failing chunk's (nothing allocated when none fails)
  int error_chunk = threads;
#pragma omp parallel num_threads(threads)
  {
    const int t = omp_get_thread_num(), count = omp_get_num_threads();
    const int chunk = ((m + count - 1) / count + 7) / 8 * 8;
    const int begin = std::min(m, t * chunk), end = std::min(m, begin + chunk);
    try {
      f(begin, end, t);
    } catch (...) {
#pragma omp critical(svmp_for_chunks_error)
      if (t < error_chunk) {
        error_chunk = t;
        error = std::current_exception();
      }
    }
  }
  if (error) std::rethrow_exception(error);
}

// Partial results of chunks (indices relative to the chunk; chunk 0 starts at 0) merged into one;
// chunks in order and strict comparisons keep the smallest index on ties.
inline loops::ArgMax mergeMax(const std::vector<loops::ArgMax>& parts,
                              const std::vector<int>& offsets) {
  loops::ArgMax best = parts[0];
  for (size_t c = 1; c < parts.size(); ++c) {
    if (parts[c].index < 0) continue;
    if (best.index < 0 || parts[c].value > best.value)
      best = {parts[c].value, parts[c].index + offsets[c]};
  }
  return best;
}

inline loops::SelectJ mergeSelectJ(const std::vector<loops::SelectJ>& parts,
                                   const std::vector<int>& offsets) {
  loops::SelectJ best = parts[0];
  for (size_t c = 1; c < parts.size(); ++c) {
    best.gmax2 = std::max(best.gmax2, parts[c].gmax2);
    if (parts[c].j < 0) continue;
    if (best.j < 0 || parts[c].obj_min < best.obj_min) {
      best.obj_min = parts[c].obj_min;
      best.j = parts[c].j + offsets[c];
    }
  }
  return best;
}

}  // namespace svmp::svm::parallel
