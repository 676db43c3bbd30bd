// The RBF kernel column and the truncated RBF sum (svm/simd_loops.hpp), vectorised and dispatched at
// run time like the SMO loops of svm/simd_loops.cpp. Compiled without contraction into FMA
// (svm/CMakeLists.txt): they fuse explicitly where they mean to, so every instruction set gives the
// same bits. Where a call might cross between code of different targets (fmaddInto, in an
// unoptimised build) vectors go by reference, so no vector-passing ABI is relied on.
#pragma GCC diagnostic ignored "-Wpsabi"

#include <cassert>
#include <cmath>

#include "svm/avx512_lanes.hpp"
#include "svm/fast_exp.hpp"
#include "svm/simd_loops.hpp"
#include "svm/simd_vectors.hpp"

namespace svmp::svm::loops {

namespace {

// a b + c rounded once: the FMA instructions on AVX-512 and AVX2, the C library's fma (which rounds
// alike) lane by lane on SSE2 machines, which have no FMA. Explicit, as the file is compiled without
// contraction (svm/CMakeLists.txt): every width and tail fuses the same operations, so all give the
// same bits. fmaddInto is not always_inline (intrinsics of a target cannot be forced into the generic
// templates, which have none); the entry points (SVMP_ENTRY) flatten it in, and its vectors go by
// reference, so an unoptimised build (no flattening) passes no wide vector between code of
// different targets.
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

// The widest loop this machine runs, for either column type.
template <typename Out>
void rbfColumnDispatch(const double* coords, long stride, int d, const double* z, double neg_gamma, int len,
                       Out* out) {
  if (usingAvx512())
    rbfColumnAvx512(coords, stride, d, z, neg_gamma, len, out);
  else if (usingAvx2())
    rbfColumnAvx2(coords, stride, d, z, neg_gamma, len, out);
  else
    rbfColumnImpl<2>(coords, stride, d, z, neg_gamma, len, out);
}

}  // namespace

void rbfColumn(const double* coords, long stride, int d, const double* z, double neg_gamma, int len,
               float* out) {
  rbfColumnDispatch(coords, stride, d, z, neg_gamma, len, out);
}

void rbfColumn(const double* coords, long stride, int d, const double* z, double neg_gamma, int len,
               double* out) {
  rbfColumnDispatch(coords, stride, d, z, neg_gamma, len, out);
}

double truncatedRbfSum(const BlockedSupportVectors& sv, const double* q, double gamma, double r2,
                       double* grad) {
  assert(sv.block % 8 == 0 && "blocks of a multiple of 8 columns (svm/simd_loops.hpp)");
  if (usingAvx512()) return truncatedRbfSumAvx512(sv, q, gamma, r2, grad);
  if (usingAvx2()) return truncatedRbfSumAvx2(sv, q, gamma, r2, grad);
  return grad ? truncatedRbfSumDispatch<2, true>(sv, q, gamma, r2, grad)
              : truncatedRbfSumDispatch<2, false>(sv, q, gamma, r2, grad);
}

}  // namespace svmp::svm::loops
