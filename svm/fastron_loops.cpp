// Vectors wider than the baseline ISA appear only inside target("avx2") / target("avx512f") functions.
#pragma GCC diagnostic ignored "-Wpsabi"

#include "svm/fastron_loops.hpp"
#include "svm/simd_loops.hpp"

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

#define SVMP_AVX2 __attribute__((target("avx2,fma")))
#define SVMP_AVX512 __attribute__((target("avx512f,fma")))
SVMP_AVX2 void columnAvx2(const PointsSoA& p, const float* z, float hg, float* out) { columnImpl(p, z, hg, out); }

// The query's hot loop, fused so that every partial sum stays in registers, and rounded alike on
// every instruction set: 16 lanes (one AVX-512 vector, two AVX2 or four SSE2 ones), lane l summing
// the points j = l (mod 16) in order; per point and block t = 1 + hg s with s the sum of squared
// differences in coordinate order, 1 / t^2 by an exact division (a reciprocal estimate's bits differ
// by instruction set), the weight's product added; every operation rounded alone, as SSE2 has no
// fused multiply-add (fusing cost SSE2 13x its speed through the C library's fmaf and gained
// AVX-512 0-3%); the lanes then added in order in double. Needs the point count padded with zero
// weights to a multiple of 16 (the model pads so).
// A macro, not a template: the Ops' intrinsics inline only into functions of their own target.
#define SVMP_LANE_SUM(Ops) \
  using Vec = Ops::Vec; \
  constexpr int kVecs = 16 / Ops::kLanes; \
  const Vec zero = Ops::set1(0.f), one = Ops::set1(1.f), vhg = Ops::set1(hg); \
  Vec acc[kVecs]; \
  for (Vec& a : acc) a = zero; \
  for (int j0 = 0; j0 < p.n; j0 += 16) \
    for (int v = 0; v < kVecs; ++v) { \
      const int j = j0 + v * Ops::kLanes; \
      Vec k = zero; \
      for (int b = 0; b < p.dim; b += p.block) { \
        Vec s = zero; \
        for (int c = b; c < b + p.block; ++c) { \
          const Vec d = Ops::sub(Ops::load(p.xs + c * p.stride + j), Ops::set1(z[c])); \
          s = Ops::add(Ops::mul(d, d), s); \
        } \
        const Vec t = Ops::add(Ops::mul(vhg, s), one); \
        k = Ops::add(k, Ops::div(one, Ops::mul(t, t))); \
      } \
      acc[v] = Ops::add(Ops::mul(Ops::load(w + j), k), acc[v]); \
    } \
  alignas(64) float lanes[16]; \
  for (int v = 0; v < kVecs; ++v) Ops::store(lanes + v * Ops::kLanes, acc[v]); \
  double total = 0; \
  for (float x : lanes) total += x; \
  return total;

struct Sse2Ops {
  using Vec = __m128;
  static constexpr int kLanes = 4;
  static SVMP_INLINE __m128 set1(float x) { return _mm_set1_ps(x); }
  static SVMP_INLINE __m128 load(const float* p) { return _mm_loadu_ps(p); }
  static SVMP_INLINE void store(float* p, __m128 a) { _mm_storeu_ps(p, a); }
  static SVMP_INLINE __m128 add(__m128 a, __m128 b) { return _mm_add_ps(a, b); }
  static SVMP_INLINE __m128 sub(__m128 a, __m128 b) { return _mm_sub_ps(a, b); }
  static SVMP_INLINE __m128 mul(__m128 a, __m128 b) { return _mm_mul_ps(a, b); }
  static SVMP_INLINE __m128 div(__m128 a, __m128 b) { return _mm_div_ps(a, b); }
};

struct Avx2Ops {
  using Vec = __m256;
  static constexpr int kLanes = 8;
  SVMP_AVX2 static SVMP_INLINE __m256 set1(float x) { return _mm256_set1_ps(x); }
  SVMP_AVX2 static SVMP_INLINE __m256 load(const float* p) { return _mm256_loadu_ps(p); }
  SVMP_AVX2 static SVMP_INLINE void store(float* p, __m256 a) { _mm256_storeu_ps(p, a); }
  SVMP_AVX2 static SVMP_INLINE __m256 add(__m256 a, __m256 b) { return _mm256_add_ps(a, b); }
  SVMP_AVX2 static SVMP_INLINE __m256 sub(__m256 a, __m256 b) { return _mm256_sub_ps(a, b); }
  SVMP_AVX2 static SVMP_INLINE __m256 mul(__m256 a, __m256 b) { return _mm256_mul_ps(a, b); }
  SVMP_AVX2 static SVMP_INLINE __m256 div(__m256 a, __m256 b) { return _mm256_div_ps(a, b); }
};

struct Avx512Ops {
  using Vec = __m512;
  static constexpr int kLanes = 16;
  SVMP_AVX512 static SVMP_INLINE __m512 set1(float x) { return _mm512_set1_ps(x); }
  SVMP_AVX512 static SVMP_INLINE __m512 load(const float* p) { return _mm512_loadu_ps(p); }
  SVMP_AVX512 static SVMP_INLINE void store(float* p, __m512 a) { _mm512_storeu_ps(p, a); }
  SVMP_AVX512 static SVMP_INLINE __m512 add(__m512 a, __m512 b) { return _mm512_add_ps(a, b); }
  SVMP_AVX512 static SVMP_INLINE __m512 sub(__m512 a, __m512 b) { return _mm512_sub_ps(a, b); }
  SVMP_AVX512 static SVMP_INLINE __m512 mul(__m512 a, __m512 b) { return _mm512_mul_ps(a, b); }
  SVMP_AVX512 static SVMP_INLINE __m512 div(__m512 a, __m512 b) { return _mm512_div_ps(a, b); }
};

double sumSse2(const PointsSoA& p, const float* w, const float* z, float hg) { SVMP_LANE_SUM(Sse2Ops) }
SVMP_AVX2 double sumAvx2(const PointsSoA& p, const float* w, const float* z, float hg) { SVMP_LANE_SUM(Avx2Ops) }
SVMP_AVX512 double sumAvx512(const PointsSoA& p, const float* w, const float* z, float hg) {
  SVMP_LANE_SUM(Avx512Ops)
}

}  // namespace

// The instruction sets svm/simd_loops.cpp dispatches to (SVMP_SIMD caps them there too).
void kernelColumn(const PointsSoA& p, const float* z, float half_gamma, float* out) {
  loops::usingAvx2() ? columnAvx2(p, z, half_gamma, out) : columnImpl(p, z, half_gamma, out);
}

double weightedSum(const PointsSoA& p, const float* weight, const float* z, float half_gamma) {
  if (loops::usingAvx512()) return sumAvx512(p, weight, z, half_gamma);
  if (loops::usingAvx2()) return sumAvx2(p, weight, z, half_gamma);
  return sumSse2(p, weight, z, half_gamma);
}

}  // namespace svmp::svm::fastron_loops
