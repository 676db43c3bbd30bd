// Kernel functions for SVM training and evaluation.
//
// Thesis ch. 2.1.3, Table 2.1 (linear, polynomial, Gaussian RBF, sigmoid); the rational quadratic
// kernel is the one of Fastron (Das, Yip, ICRA 2017); the block-sum kernel sums a base kernel over
// consecutive blocks of coordinates of a feature vector (forward-kinematics "FK kernel": a feature
// vector holds the positions of several points on the robot, one block each).
// Thread safety: Kernel is an immutable value; its methods may run concurrently.
#pragma once

#include <string>

#include "svm/fast_exp.hpp"

namespace svmp::svm {

enum class KernelType { kLinear, kPolynomial, kRbf, kSigmoid, kRationalQuadratic };

const char* kernelTypeName(KernelType type);

// The largest RBF gamma: beyond it the gradient's 2 gamma (x - q) overflows (1e308 gave NaN).
inline constexpr double kMaxRbfGamma = 1e300;

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
  static Kernel rbf(double gamma);           // throws on gamma <= 0, NaN or past kMaxRbfGamma
  static Kernel blockSum(const Kernel& base, int block);

  // True for the plain RBF kernel, which has the vectorised and truncated fast paths.
  bool isPlainRbf() const { return type == KernelType::kRbf && block == 0; }
  bool operator==(const Kernel&) const = default;

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

}  // namespace svmp::svm
