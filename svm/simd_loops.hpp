// The O(n) loops of one SMO iteration (svm/simd_loops.cpp), the RBF kernel column and the truncated
// RBF sum (svm/kernel_loops.cpp), vectorised and dispatched at run time to AVX-512 (8 lanes), AVX2
// (4 lanes) or baseline SSE2 (2 lanes);
// SVMP_SIMD=avx2 in the environment caps them at AVX2. Working-set selection is WSS2 of Fan, Chen,
// Lin, JMLR 6 (2005); the gradient update is libsvm's (Chang & Lin 2011, sec. 4.1).
#pragma once

namespace svmp::svm::loops {

struct ArgMax {
  double value;
  int index;  // -1 when no entry qualifies
};

// The solver keeps yG[t] = y_t G_t (labels +-1), so no loop needs the labels themselves.
// max_t up[t] - yG[t] (up[t] is 0 for t in I_up, -inf otherwise): the WSS "i".
ArgMax selectI(int m, const double* up, const double* yG);

struct SelectJ {
  double gmax2;    // max_{t in I_low} y_t G_t
  double obj_min;  // min second-order objective decrease; +inf if none
  int j;
};
// low[t] is 0 for t in I_low, +inf otherwise; tau replaces non-positive curvature.
SelectJ selectJ(int m, const double* low, const double* yG, const double* diag, const float* Ki,
                double kii, double gmax, double tau);

// yG[t] += wi Ki[t] + wj Kj[t]  (G_t += y_t (wi K_ti + wj K_tj) times y_t = +-1)
void updateGradient(int m, double* yG, const float* Ki, const float* Kj, double wi, double wj);
// updateGradient, then selectI(m, up, yG) on the result, in one pass over yG.
ArgMax updateGradientSelectI(int m, double* yG, const float* Ki, const float* Kj, double wi,
                             double wj, const double* up);

// out[t] = exp(-gamma |z - x_t|^2) for t in [0, len); coords has d rows of stride `stride`,
// already offset to the first sample.
void rbfColumn(const double* coords, long stride, int d, const double* z, double neg_gamma, int len,
               float* out);
void rbfColumn(const double* coords, long stride, int d, const double* z, double neg_gamma, int len,
               double* out);

// Truncated RBF sum over blocks of support vectors (thesis ch. 4.3.1): terms with squared distance
// d^2 >= r2 are zero. Blocks whose bounding sphere or box is at squared distance >= r2 are skipped.
// xs: coordinates, row k at xs + k * stride, blocks of `block` consecutive columns (block is a
// multiple of 8; padding columns have coefficient 0). lo/hi: bounding boxes, row k at k * blocks.
// Returns sum coef_s exp(-gamma d_s^2); grad (if not null) gets its gradient w.r.t. q.
struct BlockedSupportVectors {
  int d, blocks, block;
  long stride;
  const double *xs, *coef, *lo, *hi;
  const double* centre;  // bounding spheres: centre row k at k * blocks, radius per block
  const double* radius;
};
double truncatedRbfSum(const BlockedSupportVectors& sv, const double* q, double gamma, double r2,
                       double* grad);

bool usingAvx2();
bool usingAvx512();

}  // namespace svmp::svm::loops
