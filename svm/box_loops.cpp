// Compiled with -ffp-contract=off (svm/CMakeLists.txt): G + w K is rounded as a product, then a sum,
// in every lane and in the tail, as the SMO loop computes it, so both loops give the same gradients.
#include "svm/box_loops.hpp"

#include <immintrin.h>

#include <limits>

#include "svm/avx512_lanes.hpp"

namespace svmp::svm::loops {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Entries [t, m) one at a time into the two running maxima.
void boxTail(int t, int m, double* G, const float* K, double w, const double* up, const double* down,
             ArgMax& grow, ArgMax& shrink) {
  for (; t < m; ++t) {
    if (K) G[t] += w * static_cast<double>(K[t]);
    if (up[t] - G[t] > grow.value) grow = {up[t] - G[t], t};
    if (down[t] + G[t] > shrink.value) shrink = {down[t] + G[t], t};
  }
}

// A growing step wins ties: its entries come first in the doubled order.
ArgMax combine(int m, ArgMax grow, const ArgMax& shrink) {
  if (shrink.value > grow.value) grow = {shrink.value, m + shrink.index};
  if (grow.value == -kInf) grow.index = -1;
  return grow;
}

// GCC 12 warns about _mm512_undefined_pd inside its own intrinsics at -O3 (a known false positive).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#pragma GCC diagnostic ignored "-Wuninitialized"
// The growing and shrinking maxima are two independent chains of blends, so one set of lanes each
// hides the blend's latency (the SMO loop needs two sets for its one chain).
SVMP_AVX512 ArgMax updateGradientSelectBoxAvx512(int m, double* G, const float* K, double w,
                                                 const double* up, const double* down) {
  const __m512d vw = _mm512_set1_pd(w), eight = _mm512_set1_pd(8.0);
  __m512d grow = _mm512_set1_pd(-kInf), shrink = grow, grow_idx = _mm512_set1_pd(-1.0), shrink_idx = grow_idx;
  __m512d tv = _mm512_setr_pd(0, 1, 2, 3, 4, 5, 6, 7);
  int t = 0;
  for (; t + 8 <= m; t += 8, tv = _mm512_add_pd(tv, eight)) {
    __m512d g = _mm512_loadu_pd(G + t);
    if (K) {
      g = _mm512_add_pd(g, _mm512_mul_pd(vw, _mm512_cvtps_pd(_mm256_loadu_ps(K + t))));
      _mm512_storeu_pd(G + t, g);
    }
    const __m512d u = _mm512_sub_pd(_mm512_loadu_pd(up + t), g);
    const __m512d d = _mm512_add_pd(_mm512_loadu_pd(down + t), g);
    const __mmask8 u_better = _mm512_cmp_pd_mask(u, grow, _CMP_GT_OQ);
    const __mmask8 d_better = _mm512_cmp_pd_mask(d, shrink, _CMP_GT_OQ);
    grow = _mm512_mask_blend_pd(u_better, grow, u);
    grow_idx = _mm512_mask_blend_pd(u_better, grow_idx, tv);
    shrink = _mm512_mask_blend_pd(d_better, shrink, d);
    shrink_idx = _mm512_mask_blend_pd(d_better, shrink_idx, tv);
  }
  ArgMax g{-kInf, -1}, s{-kInf, -1};
  mergeLanes8<true>(grow, grow_idx, g.value, g.index);
  mergeLanes8<true>(shrink, shrink_idx, s.value, s.index);
  boxTail(t, m, G, K, w, up, down, g, s);
  return combine(m, g, s);
}
#pragma GCC diagnostic pop

}  // namespace

ArgMax updateGradientSelectBox(int m, double* G, const float* K, double w, const double* up,
                               const double* down) {
  if (usingAvx512()) return updateGradientSelectBoxAvx512(m, G, K, w, up, down);
  ArgMax g{-kInf, -1}, s{-kInf, -1};
  boxTail(0, m, G, K, w, up, down, g, s);
  return combine(m, g, s);
}

}  // namespace svmp::svm::loops
