// Kernel functions for SVM training and evaluation.
//
// Thesis ch. 2.1.3, Table 2.1 (linear, polynomial, Gaussian RBF, sigmoid); the rational quadratic
// kernel is the one of Fastron (Das, Yip, ICRA 2017); the block-sum kernel sums a base kernel over
// consecutive blocks of coordinates of a feature vector (forward-kinematics "FK kernel": a feature
// vector holds the positions of several points on the robot, one block each).
#pragma once

#include <string>

namespace svmp::svm {

enum class KernelType { kLinear, kPolynomial, kRbf, kSigmoid, kRationalQuadratic };

const char* kernelTypeName(KernelType type);

struct Kernel {
  KernelType type = KernelType::kRbf;
  // RBF: exp(-gamma |x-y|^2); rational quadratic: (1 + (gamma/2)|x-y|^2)^-2;
  // polynomial: (gamma x'y + coef0)^degree; sigmoid: tanh(gamma x'y + coef0).
  double gamma = 1.0;
  double coef0 = 0.0;
  int degree = 3;
  // 0: plain kernel over all d coordinates. b > 0: block-sum kernel, sum over the d/b consecutive
  // blocks of b coordinates of the base kernel applied to each block (d must be a multiple of b).
  int block = 0;

  static Kernel rbfFromSigma(double sigma);  // gamma = 1/(2 sigma^2); throws on sigma <= 0 or NaN
  static Kernel rbf(double gamma);           // throws on gamma <= 0 or NaN
  static Kernel blockSum(const Kernel& base, int block);

  // True for the plain RBF kernel, which has the vectorised and truncated fast paths.
  bool isPlainRbf() const { return type == KernelType::kRbf && block == 0; }

  // "" when the parameters are usable for data of dimension d, else what is wrong.
  std::string validate(int d) const;

  double value(const double* x, const double* y, int d) const;
  // d/dy k(x, y), written to grad[0..d).
  void gradientWrtY(const double* x, const double* y, int d, double* grad) const;
  // k(x, y) and d/dy k(x, y) in one pass; returns k.
  double valueAndGradientWrtY(const double* x, const double* y, int d, double* grad) const;

 private:
  double baseValue(const double* x, const double* y, int d) const;
  double baseValueAndGradient(const double* x, const double* y, int d, double* grad) const;
};

// exp(x) for x <= 0, branch-free so loops over arrays vectorise; relative error ~2e-16, returns 0
// below -700. Used in the kernel-column and evaluation hot loops instead of std::exp.
inline double expNonPositive(double x) {
  constexpr double kLog2e = 1.4426950408889634;
  constexpr double kLn2Hi = 6.93145751953125e-1;
  constexpr double kLn2Lo = 1.42860682030941723212e-6;
  constexpr double kShift = 6755399441055744.0;  // 1.5 * 2^52: rounds to integer in the low bits
  x = x < -700.0 ? -700.0 : x;
  const double t = x * kLog2e + kShift;
  const double k = t - kShift;
  const double r = (x - k * kLn2Hi) - k * kLn2Lo;  // |r| <= ln2/2
  // Taylor series to degree 12: truncation error < 2e-16 on |r| <= 0.347.
  double p = 1.0 / 479001600.0;
  p = p * r + 1.0 / 39916800.0;
  p = p * r + 1.0 / 3628800.0;
  p = p * r + 1.0 / 362880.0;
  p = p * r + 1.0 / 40320.0;
  p = p * r + 1.0 / 5040.0;
  p = p * r + 1.0 / 720.0;
  p = p * r + 1.0 / 120.0;
  p = p * r + 1.0 / 24.0;
  p = p * r + 1.0 / 6.0;
  p = p * r + 0.5;
  p = p * r + 1.0;
  p = p * r + 1.0;
  // 2^k through the exponent bits; k is in [-1010, 0] so the result stays normal.
  // k from the bits of t (no double->int64 conversion, which SSE2/AVX2 cannot vectorise).
  long long tbits;
  __builtin_memcpy(&tbits, &t, sizeof tbits);
  const long long ki = tbits - 0x4338000000000000LL;
  const unsigned long long bits = static_cast<unsigned long long>(ki + 1023) << 52;
  double scale;
  __builtin_memcpy(&scale, &bits, sizeof scale);
  return p * scale;
}

}  // namespace svmp::svm
