// Double vectors (GCC/Clang vector extensions) for the solver's O(n) loops.
//
// GCC does not vectorise min/max/argmin reductions over doubles without -ffast-math, and those
// reductions are the working-set selection of SMO (Fan, Chen, Lin 2005). Two lanes (SSE2) on
// baseline x86-64, four with AVX (-march=native): wider vectors than the ISA has are lowered
// through the stack by GCC, which is slower than scalar code.
#pragma once

#include <limits>

// Functions are inlined into their loops; the ABI note about 32-byte vectors does not apply.
#pragma GCC diagnostic ignored "-Wpsabi"

namespace svmp::svm::simd {

#ifdef __AVX__
inline constexpr int kLanes = 4;
#else
inline constexpr int kLanes = 2;
#endif
using Vd = double __attribute__((vector_size(8 * kLanes)));
using Vf = float __attribute__((vector_size(4 * kLanes)));
using Vl = long long __attribute__((vector_size(8 * kLanes)));

inline Vd load(const double* p) {
  Vd v;
  __builtin_memcpy(&v, p, sizeof v);
  return v;
}
inline Vd load(const float* p) {
  Vf v;
  __builtin_memcpy(&v, p, sizeof v);
  return __builtin_convertvector(v, Vd);
}
inline void store(double* p, Vd v) { __builtin_memcpy(p, &v, sizeof v); }
inline void store(float* p, Vd v) {
  const Vf f = __builtin_convertvector(v, Vf);
  __builtin_memcpy(p, &f, sizeof f);
}
inline Vd broadcast(double x) { return x - Vd{}; }
inline Vd max(Vd a, Vd b) { return a > b ? a : b; }
inline Vd min(Vd a, Vd b) { return a < b ? a : b; }
inline double hmax(Vd v) {
  double m = v[0];
  for (int l = 1; l < kLanes; ++l) m = v[l] > m ? v[l] : m;
  return m;
}
inline double hmin(Vd v) {
  double m = v[0];
  for (int l = 1; l < kLanes; ++l) m = v[l] < m ? v[l] : m;
  return m;
}

// Lane-wise expNonPositive (svm/kernel.hpp): same operations, so the same results.
inline Vd expNonPositive(Vd x) {
  const Vd lo = broadcast(-700.0);
  x = x < lo ? lo : x;
  const Vd shift = broadcast(6755399441055744.0);
  const Vd t = x * broadcast(1.4426950408889634) + shift;
  const Vd k = t - shift;
  const Vd r = (x - k * broadcast(6.93145751953125e-1)) - k * broadcast(1.42860682030941723212e-6);
  Vd p = broadcast(1.0 / 479001600.0);
  p = p * r + broadcast(1.0 / 39916800.0);
  p = p * r + broadcast(1.0 / 3628800.0);
  p = p * r + broadcast(1.0 / 362880.0);
  p = p * r + broadcast(1.0 / 40320.0);
  p = p * r + broadcast(1.0 / 5040.0);
  p = p * r + broadcast(1.0 / 720.0);
  p = p * r + broadcast(1.0 / 120.0);
  p = p * r + broadcast(1.0 / 24.0);
  p = p * r + broadcast(1.0 / 6.0);
  p = p * r + broadcast(0.5);
  p = p * r + broadcast(1.0);
  p = p * r + broadcast(1.0);
  const Vl ki = (Vl)t - 0x4338000000000000LL;
  const Vl bits = (ki + 1023) << 52;
  return p * (Vd)bits;
}

}  // namespace svmp::svm::simd
