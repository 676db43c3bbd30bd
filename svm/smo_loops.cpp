#include "svm/smo_loops.hpp"

#include <algorithm>
#include <limits>

#include "svm/kernel.hpp"

// Vectors wider than the baseline ISA are only used inside target("avx2") functions.
#pragma GCC diagnostic ignored "-Wpsabi"

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

// Same operations as svmp::svm::expNonPositive, lane-wise.
template <int L>
SVMP_INLINE typename V<L>::D vexp(typename V<L>::D x) {
  using D = typename V<L>::D;
  using I = typename V<L>::I;
  const D lo = splat<L>(-700.0);
  x = x < lo ? lo : x;
  const D shift = splat<L>(6755399441055744.0);
  const D t = x * splat<L>(1.4426950408889634) + shift;
  const D k = t - shift;
  const D r = (x - k * splat<L>(6.93145751953125e-1)) - k * splat<L>(1.42860682030941723212e-6);
  D p = splat<L>(1.0 / 479001600.0);
  p = p * r + splat<L>(1.0 / 39916800.0);
  p = p * r + splat<L>(1.0 / 3628800.0);
  p = p * r + splat<L>(1.0 / 362880.0);
  p = p * r + splat<L>(1.0 / 40320.0);
  p = p * r + splat<L>(1.0 / 5040.0);
  p = p * r + splat<L>(1.0 / 720.0);
  p = p * r + splat<L>(1.0 / 120.0);
  p = p * r + splat<L>(1.0 / 24.0);
  p = p * r + splat<L>(1.0 / 6.0);
  p = p * r + splat<L>(0.5);
  p = p * r + splat<L>(1.0);
  p = p * r + splat<L>(1.0);
  const I bits = (((I)t - 0x4338000000000000LL) + 1023) << 52;
  return p * (D)bits;
}

// Lane winner: largest value, smallest index on ties (deterministic for any L).
template <int L, bool kMax>
SVMP_INLINE void reduceLanes(typename V<L>::D best, typename V<L>::D idx, double& value, int& index) {
  for (int l = 0; l < L; ++l) {
    const bool better = kMax ? best[l] > value : best[l] < value;
    if (better || (best[l] == value && idx[l] < index)) {
      value = best[l];
      index = static_cast<int>(idx[l]);
    }
  }
}

template <int L>
SVMP_INLINE ArgMax selectIImpl(int m, const double* up, const double* y, const double* G) {
  using D = typename V<L>::D;
  D best = splat<L>(-kInf), idx = splat<L>(-1), tv = iota<L>(0);
  const D step = splat<L>(L);
  int t = 0;
  for (; t + L <= m; t += L) {
    const D v = load<L>(up + t) - load<L>(y + t) * load<L>(G + t);
    const auto better = v > best;
    best = better ? v : best;
    idx = better ? tv : idx;
    tv += step;
  }
  ArgMax r{-kInf, -1};
  reduceLanes<L, true>(best, idx, r.value, r.index);
  for (; t < m; ++t) {
    const double v = up[t] - y[t] * G[t];
    if (v > r.value) {
      r.value = v;
      r.index = t;
    }
  }
  if (r.value == -kInf) r.index = -1;
  return r;
}

template <int L>
SVMP_INLINE SelectJ selectJImpl(int m, const double* low, const double* y, const double* G,
                                const double* diag, const float* Ki, double kii, double gmax,
                                double tau) {
  using D = typename V<L>::D;
  const D vinf = splat<L>(kInf), vtau = splat<L>(tau), vzero = splat<L>(0.0);
  const D vgmax = splat<L>(gmax), vkii = splat<L>(kii), step = splat<L>(L);
  D g2 = splat<L>(-kInf), best = vinf, idx = splat<L>(-1), tv = iota<L>(0);
  int t = 0;
  for (; t + L <= m; t += L) {
    const D yg = load<L>(y + t) * load<L>(G + t);
    const D lowp = load<L>(low + t);
    const D c = yg - lowp;
    g2 = c > g2 ? c : g2;
    const D diff = vgmax + yg;
    D quad = vkii + load<L>(diag + t) - 2.0 * load<L>(Ki + t);
    quad = quad > vzero ? quad : vtau;
    D obj = -(diff * diff) / quad;
    obj = diff > vzero ? obj : vinf;
    obj += lowp;
    const auto better = obj < best;
    best = better ? obj : best;
    idx = better ? tv : idx;
    tv += step;
  }
  SelectJ r{-kInf, kInf, -1};
  for (int l = 0; l < L; ++l) r.gmax2 = std::max(r.gmax2, g2[l]);
  reduceLanes<L, false>(best, idx, r.obj_min, r.j);
  for (; t < m; ++t) {
    const double yg = y[t] * G[t];
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
  return r;
}

template <int L>
SVMP_INLINE void updateGradientImpl(int m, double* G, const double* y, const float* Ki,
                                    const float* Kj, double wi, double wj) {
  using D = typename V<L>::D;
  const D vwi = splat<L>(wi), vwj = splat<L>(wj);
  int t = 0;
  for (; t + L <= m; t += L)
    store<L>(G + t, load<L>(G + t) + load<L>(y + t) * (vwi * load<L>(Ki + t) + vwj * load<L>(Kj + t)));
  for (; t < m; ++t)
    G[t] += y[t] * (wi * static_cast<double>(Ki[t]) + wj * static_cast<double>(Kj[t]));
}

template <int L, typename Out>
SVMP_INLINE void rbfColumnImpl(const double* coords, long stride, int d, const double* z,
                               double neg_gamma, int len, Out* out) {
  using D = typename V<L>::D;
  constexpr int kChunk = 256;  // distances of one chunk stay in L1 between the two passes
  alignas(64) double dist[kChunk];
  for (int c = 0; c < len; c += kChunk) {
    const int cl = std::min(kChunk, len - c);
    for (int t = 0; t < cl; ++t) dist[t] = 0.0;
    for (int k = 0; k < d; ++k) {
      const double* row = coords + k * stride + c;
      const D zk = splat<L>(z[k]);
      int t = 0;
      for (; t + L <= cl; t += L) {
        const D diff = load<L>(row + t) - zk;
        store<L>(dist + t, load<L>(dist + t) + diff * diff);
      }
      for (; t < cl; ++t) dist[t] += (row[t] - z[k]) * (row[t] - z[k]);
    }
    const D ng = splat<L>(neg_gamma);
    int t = 0;
    for (; t + L <= cl; t += L) store<L>(out + c + t, vexp<L>(ng * load<L>(dist + t)));
    for (; t < cl; ++t) out[c + t] = static_cast<Out>(expNonPositive(neg_gamma * dist[t]));
  }
}

#define SVMP_AVX2 __attribute__((target("avx2")))

SVMP_AVX2 ArgMax selectIAvx2(int m, const double* up, const double* y, const double* G) {
  return selectIImpl<4>(m, up, y, G);
}
SVMP_AVX2 SelectJ selectJAvx2(int m, const double* low, const double* y, const double* G,
                              const double* diag, const float* Ki, double kii, double gmax,
                              double tau) {
  return selectJImpl<4>(m, low, y, G, diag, Ki, kii, gmax, tau);
}
SVMP_AVX2 void updateGradientAvx2(int m, double* G, const double* y, const float* Ki,
                                  const float* Kj, double wi, double wj) {
  updateGradientImpl<4>(m, G, y, Ki, Kj, wi, wj);
}
template <typename Out>
SVMP_AVX2 void rbfColumnAvx2(const double* coords, long stride, int d, const double* z,
                             double neg_gamma, int len, Out* out) {
  rbfColumnImpl<4>(coords, stride, d, z, neg_gamma, len, out);
}

const bool kHaveAvx2 = __builtin_cpu_supports("avx2");

}  // namespace

bool usingAvx2() { return kHaveAvx2; }

ArgMax selectI(int m, const double* up, const double* y, const double* G) {
  return kHaveAvx2 ? selectIAvx2(m, up, y, G) : selectIImpl<2>(m, up, y, G);
}

SelectJ selectJ(int m, const double* low, const double* y, const double* G, const double* diag,
                const float* Ki, double kii, double gmax, double tau) {
  return kHaveAvx2 ? selectJAvx2(m, low, y, G, diag, Ki, kii, gmax, tau)
                   : selectJImpl<2>(m, low, y, G, diag, Ki, kii, gmax, tau);
}

void updateGradient(int m, double* G, const double* y, const float* Ki, const float* Kj, double wi,
                    double wj) {
  if (kHaveAvx2) updateGradientAvx2(m, G, y, Ki, Kj, wi, wj);
  else updateGradientImpl<2>(m, G, y, Ki, Kj, wi, wj);
}

void rbfColumn(const double* coords, long stride, int d, const double* z, double neg_gamma, int len,
               float* out) {
  if (kHaveAvx2) rbfColumnAvx2(coords, stride, d, z, neg_gamma, len, out);
  else rbfColumnImpl<2>(coords, stride, d, z, neg_gamma, len, out);
}

void rbfColumn(const double* coords, long stride, int d, const double* z, double neg_gamma, int len,
               double* out) {
  if (kHaveAvx2) rbfColumnAvx2(coords, stride, d, z, neg_gamma, len, out);
  else rbfColumnImpl<2>(coords, stride, d, z, neg_gamma, len, out);
}

}  // namespace svmp::svm::loops
