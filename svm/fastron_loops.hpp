// The arithmetic of a Fastron model (Das & Yip 2019, sec. III-B): sums of the second-order rational
// quadratic kernel k(x, y) = (1 + (g/2)|x - y|^2)^-2, applied to whole feature vectors (Fastron RBF,
// block = dim) or to consecutive blocks of them and summed (the FK kernel: one block of 3 per control
// point, eq. 4). Points are stored as a structure of arrays in float (row k of coordinate k at
// xs + k * stride), so a query is one pass of 16-lane (AVX-512), 8-lane (AVX2) or 4-lane (SSE2)
// arithmetic over the support set, dispatched at run time as svm/simd_loops.cpp is (SVMP_SIMD).
// Both functions give the same bits on every instruction set (fastron_loops.cpp says how).
// weightedSum needs `n` padded with zero weights and zero coordinates to a multiple of 16.
// Thread safety: pure functions; scratch lives on the stack.
#pragma once

namespace svmp::svm::fastron_loops {

struct PointsSoA {
  const float* xs;  // dim rows of `stride` floats
  long stride;
  int dim;
  int block;        // coordinates per kernel block; dim is a multiple of it
  int n;            // points (columns) in use
};

// out[j] = k(x_j, z) for j in [0, n): one lazy column of the kernel matrix.
void kernelColumn(const PointsSoA& points, const float* z, float half_gamma, float* out);
// sum_j weight[j] k(x_j, z): the model's value at one query.
double weightedSum(const PointsSoA& points, const float* weight, const float* z, float half_gamma);

}  // namespace svmp::svm::fastron_loops
