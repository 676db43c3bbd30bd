// Vectors wider than the baseline ISA are used inside target("avx2,fma") / target("avx512f,fma")
// functions and the generic templates those inline or flatten in; where a call might cross between
// code of different targets (fmaddInto, in an unoptimised build) they go by reference, so no
// vector-passing ABI is relied on.
#pragma GCC diagnostic ignored "-Wpsabi"

#include "svm/simd_loops.hpp"

#include <immintrin.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <string>

#include "svm/avx512_lanes.hpp"
#include "svm/kernel.hpp"

namespace svmp::svm::loops {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// GCC ignores a dependent vector_size, hence one specialisation per width.
template <int L>
struct V;
template <>
struct V<2> {
  using D = double __attribute__((vector_size(16)));
  using F = float __attribute__((vector_size(8)));
  using I = long long __attribute__((vector_size(16)));
};
template <>
struct V<4> {
  using D = double __attribute__((vector_size(32)));
  using F = float __attribute__((vector_size(16)));
  using I = long long __attribute__((vector_size(32)));
};
template <>
struct V<8> {
  using D = double __attribute__((vector_size(64)));
  using F = float __attribute__((vector_size(32)));
  using I = long long __attribute__((vector_size(64)));
};

#define SVMP_INLINE inline __attribute__((always_inline))

template <int L>
SVMP_INLINE typename V<L>::D load(const double* p) {
  typename V<L>::D v;
  __builtin_memcpy(&v, p, sizeof v);
  return v;
}
template <int L>
SVMP_INLINE typename V<L>::D load(const float* p) {
  typename V<L>::F v;
  __builtin_memcpy(&v, p, sizeof v);
  return __builtin_convertvector(v, typename V<L>::D);
}
template <int L>
SVMP_INLINE void store(double* p, typename V<L>::D v) {
  __builtin_memcpy(p, &v, sizeof v);
}
template <int L>
SVMP_INLINE void store(float* p, typename V<L>::D v) {
  const typename V<L>::F f = __builtin_convertvector(v, typename V<L>::F);
  __builtin_memcpy(p, &f, sizeof f);
}
template <int L>
SVMP_INLINE typename V<L>::D splat(double x) {
  return x - typename V<L>::D{};
}
template <int L>
SVMP_INLINE typename V<L>::D iota(double start) {
  typename V<L>::D v;
  for (int l = 0; l < L; ++l) v[l] = start + l;
  return v;
}

// a b + c rounded once: the FMA instructions on AVX-512 and AVX2, the C library's fma (which rounds
// alike) lane by lane on SSE2 machines, which have no FMA. Explicit, as the file is compiled without
// contraction (svm/CMakeLists.txt): every width and tail fuses the same operations, so all give the
// same bits. fmaddInto is not always_inline (intrinsics of a target cannot be forced into the generic
// templates, which have none); the entry points (SVMP_ENTRY) flatten it in, and its vectors go by
// reference, so an unoptimised build (no flattening) passes no wide vector between code of
// different targets.
#define SVMP_AVX2 __attribute__((target("avx2,fma")))
#define SVMP_ENTRY __attribute__((flatten))
SVMP_AVX512 inline void fmaddInto(V<8>::D& r, const V<8>::D& a, const V<8>::D& b, const V<8>::D& c) {
  r = _mm512_fmadd_pd(a, b, c);
}
SVMP_AVX2 inline void fmaddInto(V<4>::D& r, const V<4>::D& a, const V<4>::D& b, const V<4>::D& c) {
  r = _mm256_fmadd_pd(a, b, c);
}
inline void fmaddInto(V<2>::D& r, const V<2>::D& a, const V<2>::D& b, const V<2>::D& c) {
  r = V<2>::D{__builtin_fma(a[0], b[0], c[0]), __builtin_fma(a[1], b[1], c[1])};
}
template <class D>
SVMP_INLINE D fmadd(const D& a, const D& b, const D& c) {
  D r;
  fmaddInto(r, a, b, c);
  return r;
}
template <int L>
struct FusedMulAdd {
  SVMP_INLINE typename V<L>::D operator()(typename V<L>::D p, typename V<L>::D r, typename V<L>::D c) const {
    return fmadd(p, r, c);
  }
};
struct ScalarFusedMulAdd {
  SVMP_INLINE double operator()(double p, double r, double c) const { return __builtin_fma(p, r, c); }
};

// svm/fast_exp.hpp lane-wise, its polynomial fused. kFloat: the result is stored as float (kernel
// cache), so degree 8.
template <int L, bool kFloat = false>
SVMP_INLINE typename V<L>::D vexp(typename V<L>::D x) {
  return expNonPositiveOf<kFloat ? 8 : 12, typename V<L>::D, typename V<L>::I>(x, FusedMulAdd<L>{});
}

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

// Two vectors per step: the exponential is a long dependency chain, two chains hide its latency.
// Distances accumulate in registers across the d coordinate rows (unit stride in each row).
template <int L, typename Out>
SVMP_INLINE void rbfColumnImpl(const double* coords, long stride, int d, const double* z,
                               double neg_gamma, int len, Out* out) {
  using D = typename V<L>::D;
  constexpr bool kFloat = sizeof(Out) == sizeof(float);
  const D ng = splat<L>(neg_gamma);
  int t = 0;
  for (; t + 2 * L <= len; t += 2 * L) {
    D d0 = splat<L>(0.0), d1 = splat<L>(0.0);
    const double* row = coords + t;
    for (int k = 0; k < d; ++k, row += stride) {
      const D zk = splat<L>(z[k]);
      const D a = load<L>(row) - zk, b = load<L>(row + L) - zk;
      d0 = fmadd(a, a, d0);
      d1 = fmadd(b, b, d1);
    }
    store<L>(out + t, vexp<L, kFloat>(ng * d0));
    store<L>(out + t + L, vexp<L, kFloat>(ng * d1));
  }
  for (; t < len; ++t) {
    double dist = 0.0;
    for (int k = 0; k < d; ++k) {
      const double diff = coords[k * stride + t] - z[k];
      dist = __builtin_fma(diff, diff, dist);
    }
    // The vectors' polynomial, not expNonPositive's degree 12: which entries are left to this tail
    // depends on the lane count and on where a partly cached column resumes, and a float entry must
    // not depend on either (AVX2 and AVX-512 machines, or two cache sizes, train alike).
    out[t] = static_cast<Out>(expNonPositiveOf<kFloat ? 8 : 12, double, long long>(neg_gamma * dist, ScalarFusedMulAdd{}));
  }
}

// kD > 0: the dimension as a compile-time constant (loops over coordinates unroll, the gradient
// accumulators stay in registers); kD = 0: run-time dimension up to 16.
// The terms are summed in eight lanes whatever L is (support vector s into lane s mod 8; L < 8 keeps
// 8 / L vectors, one per group of L lanes) and the lanes added in order at the end, so the rounding,
// and with it every decision the sum feeds, is the same on AVX-512, AVX2 and SSE2 machines.
template <int L, bool kGrad, int kD = 0>
SVMP_INLINE double truncatedRbfSumImpl(const BlockedSupportVectors& sv, const double* q,
                                       double gamma, double r2, double* grad) {
  using D = typename V<L>::D;
  constexpr int kMaxDim = kD > 0 ? kD : 16;
  constexpr int kGroups = 8 / L;
  const int d = kD > 0 ? kD : sv.d;
  D f[kGroups];
  D g[kGroups][kMaxDim];
  for (int a = 0; a < kGroups; ++a) {
    f[a] = splat<L>(0.0);
    for (int k = 0; k < d; ++k) g[a][k] = splat<L>(0.0);
  }
  const D ng = splat<L>(-gamma), vr2 = splat<L>(r2), zero = splat<L>(0.0);
  const double radius_of_search = std::sqrt(r2) * (1 + 1e-12);  // never prunes a term it needs
  for (int b = 0; b < sv.blocks; ++b) {
    // Sphere first: in 6-D a box of 16 points spans about half the range of every coordinate.
    double dc = 0.0;
    for (int k = 0; k < d; ++k) {
      const double c = q[k] - sv.centre[k * sv.blocks + b];
      dc += c * c;
    }
    const double reach = radius_of_search + sv.radius[b];
    if (dc >= reach * reach) continue;
    double box = 0.0;
    for (int k = 0; k < d; ++k) {
      const double lo = sv.lo[k * sv.blocks + b], hi = sv.hi[k * sv.blocks + b];
      const double c = q[k] < lo ? lo - q[k] : (q[k] > hi ? q[k] - hi : 0.0);
      box += c * c;
    }
    if (box >= r2) continue;
    // Eight support vectors a step, in kGroups vectors of L (a compile-time index: the accumulators
    // stay in registers).
    for (int s8 = b * sv.block; s8 < (b + 1) * sv.block; s8 += 8) {
#pragma GCC unroll 4
      for (int a = 0; a < kGroups; ++a) {
        const int s = s8 + a * L;
        D dist = zero;
        for (int k = 0; k < d; ++k) {
          // q - x like the brute-force reference; the squares are summed fused (unfused cost 1.2-1.4x
          // here), so a term within a rounding of the radius may pass one radius test and not the other
          const D c = splat<L>(q[k]) - load<L>(sv.xs + k * sv.stride + s);
          dist = fmadd(c, c, dist);
        }
        // Skip the exponential when no lane is inside the radius: leaves are spatially sorted, so
        // in-radius support vectors come in runs and most groups of a passing leaf are all out.
        const auto inside = dist < vr2;
        bool any = false;
        for (int l = 0; l < L; ++l) any |= inside[l] != 0;
        if (!any) continue;
        D term = load<L>(sv.coef + s) * vexp<L>(ng * dist);
        term = inside ? term : zero;
        f[a] += term;
        // sum term * x_k (reloaded from L1) instead of keeping d differences in registers
        if constexpr (kGrad)
          for (int k = 0; k < d; ++k) g[a][k] = fmadd(term, load<L>(sv.xs + k * sv.stride + s), g[a][k]);
      }
    }
  }
  double sum = 0.0;
  for (int lane = 0; lane < 8; ++lane) sum += f[lane / L][lane % L];
  if constexpr (kGrad) {
    for (int k = 0; k < d; ++k) {
      double gk = 0.0;
      for (int lane = 0; lane < 8; ++lane) gk += g[lane / L][k][lane % L];
      // d/dq exp(-gamma |x-q|^2) = 2 gamma (x - q) exp(...): sum term (x - q) = gk - q_k sum
      grad[k] = 2.0 * gamma * (gk - q[k] * sum);
    }
  }
  return sum;
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
template <typename Out>
SVMP_AVX2 SVMP_ENTRY void rbfColumnAvx2(const double* coords, long stride, int d, const double* z,
                             double neg_gamma, int len, Out* out) {
  rbfColumnImpl<4>(coords, stride, d, z, neg_gamma, len, out);
}

template <int L, bool kGrad>
SVMP_INLINE double truncatedRbfSumDispatch(const BlockedSupportVectors& sv, const double* q,
                                           double gamma, double r2, double* grad) {
  switch (sv.d) {
    case 2:
      return truncatedRbfSumImpl<L, kGrad, 2>(sv, q, gamma, r2, grad);
    case 3:
      return truncatedRbfSumImpl<L, kGrad, 3>(sv, q, gamma, r2, grad);
    case 6:
      return truncatedRbfSumImpl<L, kGrad, 6>(sv, q, gamma, r2, grad);
    case 7:
      return truncatedRbfSumImpl<L, kGrad, 7>(sv, q, gamma, r2, grad);
    default:
      return truncatedRbfSumImpl<L, kGrad>(sv, q, gamma, r2, grad);
  }
}

SVMP_AVX2 SVMP_ENTRY double truncatedRbfSumAvx2(const BlockedSupportVectors& sv, const double* q, double gamma,
                                     double r2, double* grad) {
  return grad ? truncatedRbfSumDispatch<4, true>(sv, q, gamma, r2, grad)
              : truncatedRbfSumDispatch<4, false>(sv, q, gamma, r2, grad);
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
template <typename Out>
SVMP_AVX512 SVMP_ENTRY void rbfColumnAvx512(const double* coords, long stride, int d, const double* z,
                                 double neg_gamma, int len, Out* out) {
  rbfColumnImpl<8>(coords, stride, d, z, neg_gamma, len, out);
}
SVMP_AVX512 SVMP_ENTRY double truncatedRbfSumAvx512(const BlockedSupportVectors& sv, const double* q,
                                         double gamma, double r2, double* grad) {
  return grad ? truncatedRbfSumDispatch<8, true>(sv, q, gamma, r2, grad)
              : truncatedRbfSumDispatch<8, false>(sv, q, gamma, r2, grad);
}

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

void rbfColumn(const double* coords, long stride, int d, const double* z, double neg_gamma, int len,
               float* out) {
  if (kHaveAvx512)
    rbfColumnAvx512(coords, stride, d, z, neg_gamma, len, out);
  else if (kHaveAvx2)
    rbfColumnAvx2(coords, stride, d, z, neg_gamma, len, out);
  else
    rbfColumnImpl<2>(coords, stride, d, z, neg_gamma, len, out);
}

void rbfColumn(const double* coords, long stride, int d, const double* z, double neg_gamma, int len,
               double* out) {
  if (kHaveAvx512)
    rbfColumnAvx512(coords, stride, d, z, neg_gamma, len, out);
  else if (kHaveAvx2)
    rbfColumnAvx2(coords, stride, d, z, neg_gamma, len, out);
  else
    rbfColumnImpl<2>(coords, stride, d, z, neg_gamma, len, out);
}

}  // namespace svmp::svm::loops

namespace svmp::svm::loops {

double truncatedRbfSum(const BlockedSupportVectors& sv, const double* q, double gamma, double r2,
                       double* grad) {
  assert(sv.block % 8 == 0 && "blocks of a multiple of 8 columns (svm/simd_loops.hpp)");
  if (kHaveAvx512) return truncatedRbfSumAvx512(sv, q, gamma, r2, grad);
  if (kHaveAvx2) return truncatedRbfSumAvx2(sv, q, gamma, r2, grad);
  return grad ? truncatedRbfSumDispatch<2, true>(sv, q, gamma, r2, grad)
              : truncatedRbfSumDispatch<2, false>(sv, q, gamma, r2, grad);
}

}  // namespace svmp::svm::loops
