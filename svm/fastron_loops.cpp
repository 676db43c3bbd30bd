#include "svm/fastron_loops.hpp"

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

// Roles swapped: the queries are the vectorised axis, the support points the outer loop.
SVMP_INLINE void batchImpl(const PointsSoA& p, const float* w, const float* q, long qs, int B, float hg,
                           double* out) {
  alignas(32) float acc[kChunk], t[kChunk];
  for (int b0 = 0; b0 < B; b0 += kChunk) {
    const int c = std::min(kChunk, B - b0);
    for (int bb = 0; bb < c; ++bb) acc[bb] = 0.f;
    for (int j = 0; j < p.n; ++j) {
      const float wj = w[j];
      for (int k0 = 0; k0 < p.dim; k0 += p.block) {
        for (int bb = 0; bb < c; ++bb) t[bb] = 0.f;
        for (int k = k0; k < k0 + p.block; ++k) {
          const float xk = p.xs[k * p.stride + j];
          const float* qk = q + k * qs + b0;
#pragma omp simd
          for (int bb = 0; bb < c; ++bb) {
            const float d = qk[bb] - xk;
            t[bb] += d * d;
          }
        }
#pragma omp simd
        for (int bb = 0; bb < c; ++bb) {
          const float tt = 1.f + hg * t[bb];
          acc[bb] += wj / (tt * tt);
        }
      }
    }
    for (int bb = 0; bb < c; ++bb) out[b0 + bb] = acc[bb];
  }
}

#define SVMP_AVX2 __attribute__((target("avx2,fma")))
SVMP_AVX2 void columnAvx2(const PointsSoA& p, const float* z, float hg, float* out) { columnImpl(p, z, hg, out); }
SVMP_AVX2 double sumAvx2(const PointsSoA& p, const float* w, const float* z, float hg) { return sumImpl(p, w, z, hg); }
SVMP_AVX2 void batchAvx2(const PointsSoA& p, const float* w, const float* q, long qs, int B, float hg,
                         double* out) {
  batchImpl(p, w, q, qs, B, hg, out);
}

const bool kHaveAvx2 = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");

}  // namespace

bool usingAvx2() { return kHaveAvx2; }

void kernelColumn(const PointsSoA& p, const float* z, float half_gamma, float* out) {
  kHaveAvx2 ? columnAvx2(p, z, half_gamma, out) : columnImpl(p, z, half_gamma, out);
}

double weightedSum(const PointsSoA& p, const float* weight, const float* z, float half_gamma) {
  return kHaveAvx2 ? sumAvx2(p, weight, z, half_gamma) : sumImpl(p, weight, z, half_gamma);
}

void weightedSumBatch(const PointsSoA& p, const float* weight, const float* queries, long query_stride,
                      int B, float half_gamma, double* out) {
  kHaveAvx2 ? batchAvx2(p, weight, queries, query_stride, B, half_gamma, out)
            : batchImpl(p, weight, queries, query_stride, B, half_gamma, out);
}

}  // namespace svmp::svm::fastron_loops
