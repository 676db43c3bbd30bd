// Vectors wider than the baseline ISA appear only inside target("avx2") / target("avx512f") functions.
#pragma GCC diagnostic ignored "-Wpsabi"
// GCC 12's _mm512_rcp14_ps passes _mm512_undefined_ps() as the (fully masked-off) fallback.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"

#include "svm/fastron_loops.hpp"

#include <immintrin.h>

#include <algorithm>

namespace svmp::svm::fastron_loops {
namespace {

#define SVMP_INLINE inline __attribute__((always_inline))
constexpr int kChunk = 256;  // points per pass; the chunk's partial distances stay in L1

// t[jj] = 1 + hg |x_{j0+jj} - z|^2 over the coordinates [k0, k0 + block) of the chunk.
SVMP_INLINE void blockDenominator(const PointsSoA& p, int k0, int j0, int c, const float* z, float hg,
                                  float* t) {
  for (int jj = 0; jj < c; ++jj) t[jj] = 0.f;
  for (int k = k0; k < k0 + p.block; ++k) {
    const float* x = p.xs + k * p.stride + j0;
    const float zk = z[k];
#pragma omp simd
    for (int jj = 0; jj < c; ++jj) {
      const float d = x[jj] - zk;
      t[jj] += d * d;
    }
  }
#pragma omp simd
  for (int jj = 0; jj < c; ++jj) t[jj] = 1.f + hg * t[jj];
}

SVMP_INLINE void columnImpl(const PointsSoA& p, const float* z, float hg, float* out) {
  alignas(32) float t[kChunk];
  for (int j0 = 0; j0 < p.n; j0 += kChunk) {
    const int c = std::min(kChunk, p.n - j0);
    float* o = out + j0;
    for (int jj = 0; jj < c; ++jj) o[jj] = 0.f;
    for (int k0 = 0; k0 < p.dim; k0 += p.block) {
      blockDenominator(p, k0, j0, c, z, hg, t);
#pragma omp simd
      for (int jj = 0; jj < c; ++jj) o[jj] += 1.f / (t[jj] * t[jj]);
    }
  }
}

SVMP_INLINE double sumImpl(const PointsSoA& p, const float* w, const float* z, float hg) {
  alignas(32) float t[kChunk];
  double total = 0;
  for (int j0 = 0; j0 < p.n; j0 += kChunk) {
    const int c = std::min(kChunk, p.n - j0);
    const float* wc = w + j0;
    float acc = 0.f;
    for (int k0 = 0; k0 < p.dim; k0 += p.block) {
      blockDenominator(p, k0, j0, c, z, hg, t);
#pragma omp simd reduction(+ : acc)
      for (int jj = 0; jj < c; ++jj) acc += wc[jj] / (t[jj] * t[jj]);
    }
    total += acc;
  }
  return total;
}

#define SVMP_AVX2 __attribute__((target("avx2,fma")))
#define SVMP_AVX512 __attribute__((target("avx512f,fma")))
SVMP_AVX2 void columnAvx2(const PointsSoA& p, const float* z, float hg, float* out) { columnImpl(p, z, hg, out); }

// The query's hot loop, fused so that every partial sum stays in registers: per lane one support
// point, per block 1 / t^2 from a reciprocal estimate refined by one Newton step (r (2 - t^2 r), about
// 23 correct bits from AVX2's 12, more from AVX-512's 14), then one multiply-add with the weight.
// Needs the point count padded with zero weights to a multiple of the vector width (the model pads to
// 16).
#define SVMP_FUSED_SUM(Vec, Ops, kLanes) \
 \
  constexpr int kMaxDim = 48; \
  Vec zb[kMaxDim]; \
  for (int k = 0; k < kMaxDim; ++k) zb[k] = Ops::set1(k < p.dim ? z[k] : 0.f); \
  const Vec one = Ops::set1(1.f), two = Ops::set1(2.f), vhg = Ops::set1(hg); \
  Vec acc = Ops::set1(0.f); \
  const int blocks = p.dim / p.block; \
  for (int j = 0; j < p.n; j += kLanes) { \
    Vec k = Ops::set1(0.f); \
    for (int b = 0; b < blocks; ++b) { \
      Vec s = Ops::set1(0.f); \
      for (int c = b * p.block; c < (b + 1) * p.block; ++c) { \
        const Vec d = Ops::sub(Ops::load(p.xs + c * p.stride + j), zb[c]); \
        s = Ops::fmadd(d, d, s); \
      } \
      const Vec t = Ops::fmadd(vhg, s, one); \
      const Vec t2 = Ops::mul(t, t); \
      Vec r = Ops::rcp(t2); \
      r = Ops::mul(r, Ops::fnmadd(t2, r, two)); \
      k = Ops::add(k, r); \
    } \
    acc = Ops::fmadd(Ops::load(w + j), k, acc); \
  } \
  return Ops::sum(acc);

struct Avx2Ops {
  SVMP_AVX2 static SVMP_INLINE __m256 set1(float x) { return _mm256_set1_ps(x); }
  SVMP_AVX2 static SVMP_INLINE __m256 load(const float* p) { return _mm256_loadu_ps(p); }
  SVMP_AVX2 static SVMP_INLINE __m256 add(__m256 a, __m256 b) { return _mm256_add_ps(a, b); }
  SVMP_AVX2 static SVMP_INLINE __m256 sub(__m256 a, __m256 b) { return _mm256_sub_ps(a, b); }
  SVMP_AVX2 static SVMP_INLINE __m256 mul(__m256 a, __m256 b) { return _mm256_mul_ps(a, b); }
  SVMP_AVX2 static SVMP_INLINE __m256 fmadd(__m256 a, __m256 b, __m256 c) { return _mm256_fmadd_ps(a, b, c); }
  SVMP_AVX2 static SVMP_INLINE __m256 fnmadd(__m256 a, __m256 b, __m256 c) { return _mm256_fnmadd_ps(a, b, c); }
  SVMP_AVX2 static SVMP_INLINE __m256 rcp(__m256 a) { return _mm256_rcp_ps(a); }
  SVMP_AVX2 static SVMP_INLINE double sum(__m256 a) {
    alignas(32) float v[8];
    _mm256_store_ps(v, a);
    double s = 0;
    for (float x : v) s += x;
    return s;
  }
};

struct Avx512Ops {
  SVMP_AVX512 static SVMP_INLINE __m512 set1(float x) { return _mm512_set1_ps(x); }
  SVMP_AVX512 static SVMP_INLINE __m512 load(const float* p) { return _mm512_loadu_ps(p); }
  SVMP_AVX512 static SVMP_INLINE __m512 add(__m512 a, __m512 b) { return _mm512_add_ps(a, b); }
  SVMP_AVX512 static SVMP_INLINE __m512 sub(__m512 a, __m512 b) { return _mm512_sub_ps(a, b); }
  SVMP_AVX512 static SVMP_INLINE __m512 mul(__m512 a, __m512 b) { return _mm512_mul_ps(a, b); }
  SVMP_AVX512 static SVMP_INLINE __m512 fmadd(__m512 a, __m512 b, __m512 c) { return _mm512_fmadd_ps(a, b, c); }
  SVMP_AVX512 static SVMP_INLINE __m512 fnmadd(__m512 a, __m512 b, __m512 c) { return _mm512_fnmadd_ps(a, b, c); }
  SVMP_AVX512 static SVMP_INLINE __m512 rcp(__m512 a) { return _mm512_rcp14_ps(a); }
  SVMP_AVX512 static SVMP_INLINE double sum(__m512 a) {
    alignas(64) float v[16];
    _mm512_store_ps(v, a);
    double s = 0;
    for (float x : v) s += x;
    return s;
  }
};

SVMP_AVX2 double sumAvx2(const PointsSoA& p, const float* w, const float* z, float hg) {
  SVMP_FUSED_SUM(__m256, Avx2Ops, 8)
}
SVMP_AVX512 double sumAvx512(const PointsSoA& p, const float* w, const float* z, float hg) {
  SVMP_FUSED_SUM(__m512, Avx512Ops, 16)
}

const bool kHaveAvx2 = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
const bool kHaveAvx512 = kHaveAvx2 && __builtin_cpu_supports("avx512f");

}  // namespace

bool usingAvx2() { return kHaveAvx2; }

void kernelColumn(const PointsSoA& p, const float* z, float half_gamma, float* out) {
  kHaveAvx2 ? columnAvx2(p, z, half_gamma, out) : columnImpl(p, z, half_gamma, out);
}

double weightedSum(const PointsSoA& p, const float* weight, const float* z, float half_gamma) {
  if (p.dim <= 48 && kHaveAvx512) return sumAvx512(p, weight, z, half_gamma);
  if (p.dim <= 48 && kHaveAvx2) return sumAvx2(p, weight, z, half_gamma);
  return sumImpl(p, weight, z, half_gamma);
}

}  // namespace svmp::svm::fastron_loops
