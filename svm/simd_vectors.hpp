// Internal to svm/simd_loops.cpp and svm/kernel_loops.cpp (installed with the other headers): GCC
// vectors of 2, 4 and 8 doubles and the loads, stores and broadcasts their loops share, and the
// AVX2 target attribute (the AVX-512 one is svm/avx512_lanes.hpp's). Vectors wider than the baseline
// ISA are used only inside target("avx2,fma") / target("avx512f,fma") functions and the generic
// templates they inline; includers silence -Wpsabi, which warns about the ABI of those templates.
#pragma once

#include <immintrin.h>

namespace svmp::svm::loops {

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

#define SVMP_AVX2 __attribute__((target("avx2,fma")))

}  // namespace svmp::svm::loops
