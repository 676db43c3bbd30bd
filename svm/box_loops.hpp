// The O(m) loop of the fixed-bias neighbourhood solver (svm/local_one_vs_rest.cpp): greedy coordinate
// descent on a box-constrained QP, one gradient entry per coordinate. The SMO loops
// (svm/simd_loops.hpp) would see each coordinate twice (G_t to grow a_t, -G_t to shrink it), so each
// iteration read and wrote twice the entries and a second column of zero weight.
// Dispatched at run time to AVX-512, with a one-at-a-time baseline; both give the same result.
#pragma once

#include "svm/simd_loops.hpp"

namespace svmp::svm::loops {

// G[t] += w K[t] for t in [0, m) (skipped when K is null), then the largest KKT violation: the
// largest of up[t] - G[t] (up[t] is 0 while a_t may grow, -inf otherwise) as index t and of
// down[t] + G[t] (0 while a_t may shrink) as index m + t; the smallest index on ties, -1 when none.
ArgMax updateGradientSelectBox(int m, double* G, const float* K, double w, const double* up,
                               const double* down);

}  // namespace svmp::svm::loops
