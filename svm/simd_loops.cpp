// The SMO loops of svm/simd_loops.hpp (working-set selection, gradient update) on 8, 4 or 2 lanes,
// and the run-time choice of width that svm/kernel_loops.cpp's kernel loops follow too. Compiled
// without contraction into FMA (svm/CMakeLists.txt), so every width rounds alike.
#pragma GCC diagnostic ignored "-Wpsabi"

#include "svm/simd_loops.hpp"

#include <immintrin.h>

#include <algorithm>
#include <cstdlib>
#include <limits>
#include <string>

#include "svm/avx512_lanes.hpp"
#include "svm/simd_vectors.hpp"

namespace svmp::svm::loops {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Lane winner: largest value, smallest index on ties (deterministic for any L).
template <int L, bool kMax>
SVMP_INLINE void reduceLanes(typename V<L>::D best, typename V<L>::D idx, double& value,
                             int& index) {
  for (int l = 0; l < L; ++l) {
    const bool better = kMax ? best[l] > value : best[l] < value;
    if (better || (best[l] == value && idx[l] < index)) {
      value = best[l];
      index = static_cast<int>(idx[l]);
    }
  }
}

// Entries [t, m) of maxUpMinusYG one at a time, after the vector lanes were reduced into r.
template <bool kUpdate>
SVMP_INLINE void maxUpMinusYGTail(int t, int m, double* yG, const float* Ki, const float* Kj, double wi,
                                  double wj, const double* up, ArgMax& r) {
  for (; t < m; ++t) {
    if constexpr (kUpdate)
      yG[t] += wi * static_cast<double>(Ki[t]) + wj * static_cast<double>(Kj[t]);
    const double v = up[t] - yG[t];
    if (v > r.value) {
      r.value = v;
      r.index = t;
    }
  }
  if (r.value == -kInf) r.index = -1;
}

// max_t up[t] - yG[t] with its index; kUpdate: first yG[t] += wi Ki[t] + wj Kj[t] (the gradient
// update), so the next iteration's i comes out of the same pass with the same lanes and tie rule.
template <int L, bool kUpdate>
SVMP_INLINE ArgMax maxUpMinusYG(int m, double* yG, const float* Ki, const float* Kj, double wi,
                                double wj, const double* up) {
  using D = typename V<L>::D;
  const D vwi = splat<L>(wi), vwj = splat<L>(wj), step = splat<L>(L);
  D best = splat<L>(-kInf), idx = splat<L>(-1), tv = iota<L>(0);
  int t = 0;
  for (; t + L <= m; t += L) {
    D g = load<L>(yG + t);
    if constexpr (kUpdate) {
      g += vwi * load<L>(Ki + t) + vwj * load<L>(Kj + t);
      store<L>(yG + t, g);
    }
    const D v = load<L>(up + t) - g;
    const auto better = v > best;
    best = better ? v : best;
    idx = better ? tv : idx;
    tv += step;
  }
  ArgMax r{-kInf, -1};
  reduceLanes<L, true>(best, idx, r.value, r.index);
  maxUpMinusYGTail<kUpdate>(t, m, yG, Ki, Kj, wi, wj, up, r);
  return r;
}

// yG is only read here.
template <int L>
SVMP_INLINE ArgMax selectIImpl(int m, const double* up, const double* yG) {
  return maxUpMinusYG<L, false>(m, const_cast<double*>(yG), nullptr, nullptr, 0.0, 0.0, up);
}

template <int L>
SVMP_INLINE ArgMax updateGradientSelectIImpl(int m, double* yG, const float* Ki, const float* Kj,
                                             double wi, double wj, const double* up) {
  return maxUpMinusYG<L, true>(m, yG, Ki, Kj, wi, wj, up);
}

// Entries [t, m) of selectJ one at a time, after the vector lanes were reduced into r.
SVMP_INLINE void selectJTail(int t, int m, const double* low, const double* yG, const double* diag,
                             const float* Ki, double kii, double gmax, double tau, SelectJ& r) {
  for (; t < m; ++t) {
    const double yg = yG[t];
    r.gmax2 = std::max(r.gmax2, yg - low[t]);
    const double diff = gmax + yg;
    double quad = kii + diag[t] - 2.0 * static_cast<double>(Ki[t]);
    quad = quad > 0.0 ? quad : tau;
    double obj = diff > 0.0 ? -(diff * diff) / quad : kInf;
    obj += low[t];
    if (obj < r.obj_min) {
      r.obj_min = obj;
      r.j = t;
    }
  }
  if (r.obj_min == kInf) r.j = -1;
}

// The WSS2 objective -(gmax + y_t G_t)^2 / quad_t is compared as a fraction (a^2 qb > b^2 qa), not
// divided: a vector division per entry made this loop the most expensive of an iteration. Lanes are
// merged by the quotient, so two objectives within a rounding of each other may be chosen apart by
// different widths (the one exception to their giving the same bits).
template <int L>
SVMP_INLINE SelectJ selectJImpl(int m, const double* low, const double* yG, const double* diag,
                                const float* Ki, double kii, double gmax, double tau) {
  using D = typename V<L>::D;
  const D vinf = splat<L>(kInf), vtau = splat<L>(tau), vzero = splat<L>(0.0);
  const D vgmax = splat<L>(gmax), vkii = splat<L>(kii), step = splat<L>(L);
  const D vminus = splat<L>(-1.0);
  D g2 = splat<L>(-kInf), best_num = vzero, best_quad = splat<L>(1.0), idx = vminus;
  D tv = iota<L>(0);
  int t = 0;
  for (; t + L <= m; t += L) {
    const D yg = load<L>(yG + t);
    const D lowp = load<L>(low + t);
    const D c = yg - lowp;
    g2 = c > g2 ? c : g2;
    const D diff = vgmax + yg;
    D quad = vkii + load<L>(diag + t) - 2.0 * load<L>(Ki + t);
    quad = quad > vzero ? quad : vtau;
    // Lanes outside I_low or with diff <= 0 get a negative numerator, which never wins; one select
    // per condition (GCC scalarises a conjunction of vector masks).
    D num = diff > vzero ? diff * diff : vminus;
    num = lowp == vzero ? num : vminus;
    const auto better = num * best_quad > best_num * quad;
    best_num = better ? num : best_num;
    best_quad = better ? quad : best_quad;
    idx = better ? tv : idx;
    tv += step;
  }
  D best = -(best_num / best_quad);
  best = idx < vzero ? vinf : best;
  SelectJ r{-kInf, kInf, -1};
  for (int l = 0; l < L; ++l) r.gmax2 = std::max(r.gmax2, g2[l]);
  reduceLanes<L, false>(best, idx, r.obj_min, r.j);
  selectJTail(t, m, low, yG, diag, Ki, kii, gmax, tau, r);
  return r;
}

template <int L>
SVMP_INLINE void updateGradientImpl(int m, double* yG, const float* Ki, const float* Kj, double wi,
                                    double wj) {
  using D = typename V<L>::D;
  const D vwi = splat<L>(wi), vwj = splat<L>(wj);
  int t = 0;
  for (; t + L <= m; t += L)
    store<L>(yG + t, load<L>(yG + t) + (vwi * load<L>(Ki + t) + vwj * load<L>(Kj + t)));
  for (; t < m; ++t) yG[t] += wi * static_cast<double>(Ki[t]) + wj * static_cast<double>(Kj[t]);
}


SVMP_AVX2 ArgMax selectIAvx2(int m, const double* up, const double* yG) {
  return selectIImpl<4>(m, up, yG);
}
SVMP_AVX2 SelectJ selectJAvx2(int m, const double* low, const double* yG, const double* diag,
                              const float* Ki, double kii, double gmax, double tau) {
  return selectJImpl<4>(m, low, yG, diag, Ki, kii, gmax, tau);
}
SVMP_AVX2 void updateGradientAvx2(int m, double* yG, const float* Ki, const float* Kj, double wi,
                                  double wj) {
  updateGradientImpl<4>(m, yG, Ki, Kj, wi, wj);
}
SVMP_AVX2 ArgMax updateGradientSelectIAvx2(int m, double* yG, const float* Ki, const float* Kj,
                                           double wi, double wj, const double* up) {
  return updateGradientSelectIImpl<4>(m, yG, Ki, Kj, wi, wj, up);
}

SVMP_AVX512 ArgMax selectIAvx512(int m, const double* up, const double* yG) {
  return selectIImpl<8>(m, up, yG);
}
// GCC 12 warns about _mm512_undefined_pd inside its own intrinsics at -O3 (a known false positive).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#pragma GCC diagnostic ignored "-Wuninitialized"
// selectJImpl and updateGradientSelectIImpl with AVX-512 intrinsics: GCC 12 turns the vector-extension
// selects of their <8> forms into one scalar compare per lane (3x slower than AVX2); mask registers
// keep them in vectors. Each runs two sets of lanes (entries t and t + 8 of every 16): the best-so-far
// blend is a dependency chain from one step to the next, and two chains hide its latency (solves
// 13-18% faster at 400-2,000 samples, docs/benchmarks.md).

// The best-so-far entries of 8 lanes of selectJAvx512: the WSS2 fraction num/quad and its index.
struct SelectJLanes {
  __m512d g2, num, quad, idx;
};
// Entries [t, t + 8) into the lanes (tv: their indices as doubles).
SVMP_AVX512 inline void selectJStep(SelectJLanes& s, int t, __m512d tv, const double* low, const double* yG,
                                    const double* diag, const float* Ki, __m512d vkii, __m512d vgmax,
                                    __m512d vtau) {
  const __m512d vzero = _mm512_setzero_pd(), vtwo = _mm512_set1_pd(2.0);
  const __m512d yg = _mm512_loadu_pd(yG + t);
  const __m512d lowp = _mm512_loadu_pd(low + t);
  s.g2 = _mm512_max_pd(s.g2, _mm512_sub_pd(yg, lowp));
  const __m512d diff = _mm512_add_pd(vgmax, yg);
  const __m512d kit = _mm512_cvtps_pd(_mm256_loadu_ps(Ki + t));
  __m512d quad = _mm512_sub_pd(_mm512_add_pd(vkii, _mm512_loadu_pd(diag + t)), _mm512_mul_pd(vtwo, kit));
  quad = _mm512_mask_blend_pd(_mm512_cmp_pd_mask(quad, vzero, _CMP_GT_OQ), vtau, quad);
  const __m512d num = _mm512_mul_pd(diff, diff);
  const __mmask8 better =
      _mm512_cmp_pd_mask(diff, vzero, _CMP_GT_OQ) & _mm512_cmp_pd_mask(lowp, vzero, _CMP_EQ_OQ) &
      _mm512_cmp_pd_mask(_mm512_mul_pd(num, s.quad), _mm512_mul_pd(s.num, quad), _CMP_GT_OQ);
  s.num = _mm512_mask_blend_pd(better, s.num, num);
  s.quad = _mm512_mask_blend_pd(better, s.quad, quad);
  s.idx = _mm512_mask_blend_pd(better, s.idx, tv);
}
SVMP_AVX512 SelectJ selectJAvx512(int m, const double* low, const double* yG, const double* diag,
                                  const float* Ki, double kii, double gmax, double tau) {
  const __m512d vtau = _mm512_set1_pd(tau), vgmax = _mm512_set1_pd(gmax), vkii = _mm512_set1_pd(kii);
  const __m512d eight = _mm512_set1_pd(8.0), sixteen = _mm512_set1_pd(16.0);
  SelectJLanes a{_mm512_set1_pd(-kInf), _mm512_setzero_pd(), _mm512_set1_pd(1.0), _mm512_set1_pd(-1.0)}, b = a;
  __m512d tv = _mm512_setr_pd(0, 1, 2, 3, 4, 5, 6, 7);
  int t = 0;
  for (; t + 16 <= m; t += 16, tv = _mm512_add_pd(tv, sixteen)) {
    selectJStep(a, t, tv, low, yG, diag, Ki, vkii, vgmax, vtau);
    selectJStep(b, t + 8, _mm512_add_pd(tv, eight), low, yG, diag, Ki, vkii, vgmax, vtau);
  }
  if (t + 8 <= m) selectJStep(a, t, tv, low, yG, diag, Ki, vkii, vgmax, vtau), t += 8;
  SelectJ r{-kInf, kInf, -1};
  for (int l = 0; l < 8; ++l) r.gmax2 = std::max({r.gmax2, a.g2[l], b.g2[l]});
  // Each set's objectives -(num / quad), +inf where no entry qualified, merged as selectJImpl's lanes.
  for (const SelectJLanes* s : {&a, &b}) {
    const __m512d obj = _mm512_mul_pd(_mm512_set1_pd(-1.0), _mm512_div_pd(s->num, s->quad));
    const __mmask8 none = _mm512_cmp_pd_mask(s->idx, _mm512_setzero_pd(), _CMP_LT_OQ);
    mergeLanes8<false>(_mm512_mask_blend_pd(none, obj, _mm512_set1_pd(kInf)), s->idx, r.obj_min, r.j);
  }
  selectJTail(t, m, low, yG, diag, Ki, kii, gmax, tau, r);
  return r;
}
SVMP_AVX512 void updateGradientAvx512(int m, double* yG, const float* Ki, const float* Kj,
                                      double wi, double wj) {
  updateGradientImpl<8>(m, yG, Ki, Kj, wi, wj);
}
// Entries [t, t + 8) of updateGradientSelectIAvx512: the update, then the running max of up - yG.
SVMP_AVX512 inline void updateSelectIStep(int t, __m512d tv, double* yG, const float* Ki, const float* Kj,
                                          __m512d vwi, __m512d vwj, const double* up, __m512d& best,
                                          __m512d& idx) {
  // g + (wi Ki + wj Kj), each operation rounded as in the generic loop.
  const __m512d ki = _mm512_mul_pd(vwi, _mm512_cvtps_pd(_mm256_loadu_ps(Ki + t)));
  const __m512d kj = _mm512_mul_pd(vwj, _mm512_cvtps_pd(_mm256_loadu_ps(Kj + t)));
  const __m512d g = _mm512_add_pd(_mm512_loadu_pd(yG + t), _mm512_add_pd(ki, kj));
  _mm512_storeu_pd(yG + t, g);
  const __m512d v = _mm512_sub_pd(_mm512_loadu_pd(up + t), g);
  const __mmask8 better = _mm512_cmp_pd_mask(v, best, _CMP_GT_OQ);
  best = _mm512_mask_blend_pd(better, best, v);
  idx = _mm512_mask_blend_pd(better, idx, tv);
}
// The same result as updateGradientSelectIImpl<8>: the largest value, the smallest index on ties.
SVMP_AVX512 ArgMax updateGradientSelectIAvx512(int m, double* yG, const float* Ki,
                                               const float* Kj, double wi, double wj,
                                               const double* up) {
  const __m512d vwi = _mm512_set1_pd(wi), vwj = _mm512_set1_pd(wj);
  const __m512d eight = _mm512_set1_pd(8.0), sixteen = _mm512_set1_pd(16.0);
  __m512d best_a = _mm512_set1_pd(-kInf), idx_a = _mm512_set1_pd(-1.0), best_b = best_a, idx_b = idx_a;
  __m512d tv = _mm512_setr_pd(0, 1, 2, 3, 4, 5, 6, 7);
  int t = 0;
  for (; t + 16 <= m; t += 16, tv = _mm512_add_pd(tv, sixteen)) {
    updateSelectIStep(t, tv, yG, Ki, Kj, vwi, vwj, up, best_a, idx_a);
    updateSelectIStep(t + 8, _mm512_add_pd(tv, eight), yG, Ki, Kj, vwi, vwj, up, best_b, idx_b);
  }
  if (t + 8 <= m) updateSelectIStep(t, tv, yG, Ki, Kj, vwi, vwj, up, best_a, idx_a), t += 8;
  ArgMax r{-kInf, -1};
  mergeLanes8<true>(best_a, idx_a, r.value, r.index);
  mergeLanes8<true>(best_b, idx_b, r.value, r.index);
  maxUpMinusYGTail<true>(t, m, yG, Ki, Kj, wi, wj, up, r);
  return r;
}
#pragma GCC diagnostic pop

// SVMP_SIMD=avx2 keeps a machine with AVX-512 on the 4-lane loops (to measure what 8 lanes give);
// SVMP_SIMD=sse2 on the 2-lane ones (the tests run all three); unset or any other value: the widest
// this machine has.
const std::string kSimdCap = std::getenv("SVMP_SIMD") ? std::getenv("SVMP_SIMD") : "";
const bool kHaveAvx2 = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") && kSimdCap != "sse2";
const bool kHaveAvx512 =
    __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("fma") && kSimdCap != "avx2" && kSimdCap != "sse2";

}  // namespace

bool usingAvx2() { return kHaveAvx2; }
bool usingAvx512() { return kHaveAvx512; }

ArgMax selectI(int m, const double* up, const double* yG) {
  if (kHaveAvx512) return selectIAvx512(m, up, yG);
  return kHaveAvx2 ? selectIAvx2(m, up, yG) : selectIImpl<2>(m, up, yG);
}

SelectJ selectJ(int m, const double* low, const double* yG, const double* diag, const float* Ki,
                double kii, double gmax, double tau) {
  if (kHaveAvx512) return selectJAvx512(m, low, yG, diag, Ki, kii, gmax, tau);
  return kHaveAvx2 ? selectJAvx2(m, low, yG, diag, Ki, kii, gmax, tau)
                   : selectJImpl<2>(m, low, yG, diag, Ki, kii, gmax, tau);
}

void updateGradient(int m, double* yG, const float* Ki, const float* Kj, double wi, double wj) {
  if (kHaveAvx512)
    updateGradientAvx512(m, yG, Ki, Kj, wi, wj);
  else if (kHaveAvx2)
    updateGradientAvx2(m, yG, Ki, Kj, wi, wj);
  else
    updateGradientImpl<2>(m, yG, Ki, Kj, wi, wj);
}

ArgMax updateGradientSelectI(int m, double* yG, const float* Ki, const float* Kj, double wi,
                             double wj, const double* up) {
  if (kHaveAvx512) return updateGradientSelectIAvx512(m, yG, Ki, Kj, wi, wj, up);
  if (kHaveAvx2) return updateGradientSelectIAvx2(m, yG, Ki, Kj, wi, wj, up);
  return updateGradientSelectIImpl<2>(m, yG, Ki, Kj, wi, wj, up);
}

}  // namespace svmp::svm::loops
