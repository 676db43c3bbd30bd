// Pieces shared by the AVX-512 loops of svm/simd_loops.cpp, svm/kernel_loops.cpp and svm/box_loops.cpp;
// internal to them (target attributes and intrinsics), though installed with the other headers.
#pragma once

#include <immintrin.h>

#define SVMP_AVX512 __attribute__((target("avx512f,fma")))

namespace svmp::svm::loops {

// The best of 8 lanes (the largest value for kMax, else the smallest; the smallest index among the
// lanes holding it) merged into (value, index) by the same rule, without branches: their outcome is
// data-dependent, so a loop over the lanes mispredicts, and cost as much as a pass over the entries.
// Lanes with no entry hold -inf (kMax) or +inf and index -1.
// GCC 12 reports the reductions' _mm512_undefined_pd as uninitialized (a false positive): callers
// compile them between `#pragma GCC diagnostic ignored` of -Wuninitialized and -Wmaybe-uninitialized.
template <bool kMax>
SVMP_AVX512 inline void mergeLanes8(__m512d best, __m512d idx, double& value, int& index) {
  const double v = kMax ? _mm512_reduce_max_pd(best) : _mm512_reduce_min_pd(best);
  const __mmask8 at = _mm512_cmp_pd_mask(best, _mm512_set1_pd(v), _CMP_EQ_OQ);
  const int i = static_cast<int>(_mm512_mask_reduce_min_pd(at, idx));
  if ((kMax ? v > value : v < value) || (v == value && i < index)) value = v, index = i;
}

}  // namespace svmp::svm::loops
