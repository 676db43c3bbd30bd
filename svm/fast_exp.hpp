#pragma once
// exp(x) for x <= 0, branch-free so loops over arrays vectorise, written once for a scalar double and
// for GCC vectors of doubles (svm/kernel_loops.cpp): Cody-Waite range reduction x = k ln2 + r with
// |r| <= ln2/2, a Taylor polynomial of degree kDegree in r, and 2^k through the exponent bits (k from
// the bits of the shifted sum, since SSE2/AVX2 cannot convert double to int64). Degree 12: relative
// error < 2e-16; degree 8: < 3e-10 (enough for values stored as float). Below -700 the result is
// exp(-700), not 0, so 2^k stays normal.
#include <cstdint>

namespace svmp::svm {

inline constexpr double kInverseFactorial[13] = {
    1.0,           1.0,            0.5,             1.0 / 6.0,        1.0 / 24.0,
    1.0 / 120.0,   1.0 / 720.0,    1.0 / 5040.0,    1.0 / 40320.0,    1.0 / 362880.0,
    1.0 / 3628800.0, 1.0 / 39916800.0, 1.0 / 479001600.0};

// p * r + c (two roundings where the compiler does not contract them; the dispatched loops, compiled
// without contraction, pass a fused multiply-add instead: svm/kernel_loops.cpp).
struct MulThenAdd {
  template <class D>
  D operator()(D p, D r, D c) const {
    return p * r + c;
  }
};

// D: double or a GCC vector of doubles; I: the same-sized integer type (long long or its vector).
// `madd(p, r, c)`: the polynomial's Horner step p r + c.
template <int kDegree, class D, class I, class MulAdd = MulThenAdd>
inline __attribute__((always_inline)) D expNonPositiveOf(D x, MulAdd madd = {}) {
  static_assert(kDegree >= 1 && kDegree <= 12);
  const D lo = D{} - 700.0;
  x = x < lo ? lo : x;
  constexpr double kShift = 6755399441055744.0;  // 1.5 * 2^52: rounds to an integer in the low bits
  const D t = x * 1.4426950408889634 + kShift;
  const D k = t - kShift;
  const D r = (x - k * 6.93145751953125e-1) - k * 1.42860682030941723212e-6;  // ln2 split hi + lo
  D p = D{} + kInverseFactorial[kDegree];
#pragma GCC unroll 12
  for (int i = kDegree - 1; i >= 0; --i) p = madd(p, r, D{} + kInverseFactorial[i]);
  const I bits = (__builtin_bit_cast(I, t) - 0x4338000000000000LL + 1023) << 52;
  return p * __builtin_bit_cast(D, bits);
}

inline double expNonPositive(double x) { return expNonPositiveOf<12, double, long long>(x); }

}  // namespace svmp::svm
