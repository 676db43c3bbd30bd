#include "svm/kernel.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace svmp::svm {

const char* kernelTypeName(KernelType type) {
  switch (type) {
    case KernelType::kLinear:
      return "linear";
    case KernelType::kPolynomial:
      return "polynomial";
    case KernelType::kRbf:
      return "rbf";
    case KernelType::kSigmoid:
      return "sigmoid";
    case KernelType::kRationalQuadratic:
      return "rational-quadratic";
  }
  return "unknown";
}

Kernel Kernel::rbfFromSigma(double sigma) {
  if (!(sigma > 0.0) || !std::isfinite(sigma)) {
    std::ostringstream msg;
    msg << "Kernel::rbfFromSigma: sigma must be positive and finite, got " << sigma;
    throw std::invalid_argument(msg.str());
  }
  return rbf(1.0 / (2.0 * sigma * sigma));
}

Kernel Kernel::rbf(double gamma) {
  if (!(gamma > 0.0 && gamma <= kMaxRbfGamma)) {  // beyond, the gradient's 2 gamma (x - q) overflows to NaN
    std::ostringstream msg;
    msg << "Kernel::rbf: gamma must be positive and at most 1e300, got " << gamma;
    throw std::invalid_argument(msg.str());
  }
  Kernel k;
  k.type = KernelType::kRbf;
  k.gamma = gamma;
  return k;
}

Kernel Kernel::blockSum(const Kernel& base, int block) {
  if (block <= 0) throw std::invalid_argument("Kernel::blockSum: block size must be positive");
  Kernel k = base;
  k.block = block;
  return k;
}

std::string Kernel::validate(int d) const {
  std::ostringstream msg;
  if (!std::isfinite(gamma) || !std::isfinite(coef0)) {
    msg << "kernel parameters must be finite (gamma " << gamma << ", coef0 " << coef0 << ")";
  } else if (type != KernelType::kLinear && !(gamma > 0.0)) {
    msg << kernelTypeName(type) << " kernel needs gamma > 0, got " << gamma;
  } else if (type == KernelType::kPolynomial && degree < 1) {
    msg << "polynomial kernel needs degree >= 1, got " << degree;
  } else if (block < 0) {
    msg << "kernel block size must be >= 0, got " << block;
  } else if (d <= 0) {
    msg << "data dimension must be positive, got " << d;
  } else if (block > 0 && d % block != 0) {
    msg << "block-sum kernel: dimension " << d << " is not a multiple of the block size " << block;
  }
  return msg.str();
}

double Kernel::baseValue(const double* x, const double* y, int d) const {
  switch (type) {
    case KernelType::kRbf:
    case KernelType::kRationalQuadratic: {
      double s = 0.0;
      for (int k = 0; k < d; ++k) s += (x[k] - y[k]) * (x[k] - y[k]);
      if (type == KernelType::kRbf) return std::exp(-gamma * s);
      const double b = 1.0 + 0.5 * gamma * s;
      return 1.0 / (b * b);
    }
    default: {
      double dot = 0.0;
      for (int k = 0; k < d; ++k) dot += x[k] * y[k];
      if (type == KernelType::kLinear) return dot;
      if (type == KernelType::kPolynomial) return std::pow(gamma * dot + coef0, degree);
      return std::tanh(gamma * dot + coef0);
    }
  }
}

double Kernel::baseValueAndGradient(const double* x, const double* y, int d, double* grad) const {
  switch (type) {
    case KernelType::kRbf: {
      double s = 0.0;
      for (int k = 0; k < d; ++k) s += (x[k] - y[k]) * (x[k] - y[k]);
      const double v = std::exp(-gamma * s);
      for (int k = 0; k < d; ++k) grad[k] = 2.0 * gamma * v * (x[k] - y[k]);
      return v;
    }
    case KernelType::kRationalQuadratic: {
      double s = 0.0;
      for (int k = 0; k < d; ++k) s += (x[k] - y[k]) * (x[k] - y[k]);
      const double b = 1.0 + 0.5 * gamma * s;
      const double inv = 1.0 / b;
      // d/dy b^-2 = -2 b^-3 * gamma (y - x)
      const double f = 2.0 * gamma * inv * inv * inv;
      for (int k = 0; k < d; ++k) grad[k] = f * (x[k] - y[k]);
      return inv * inv;
    }
    case KernelType::kLinear: {
      double dot = 0.0;
      for (int k = 0; k < d; ++k) {
        dot += x[k] * y[k];
        grad[k] = x[k];
      }
      return dot;
    }
    case KernelType::kPolynomial: {
      double dot = 0.0;
      for (int k = 0; k < d; ++k) dot += x[k] * y[k];
      const double base = gamma * dot + coef0;
      const double f = degree * std::pow(base, degree - 1) * gamma;
      for (int k = 0; k < d; ++k) grad[k] = f * x[k];
      return std::pow(base, degree);
    }
    case KernelType::kSigmoid: {
      double dot = 0.0;
      for (int k = 0; k < d; ++k) dot += x[k] * y[k];
      const double v = std::tanh(gamma * dot + coef0);
      const double f = (1.0 - v * v) * gamma;
      for (int k = 0; k < d; ++k) grad[k] = f * x[k];
      return v;
    }
  }
  return 0.0;
}

double Kernel::value(const double* x, const double* y, int d) const {
  if (block <= 0) return baseValue(x, y, d);
  double sum = 0.0;
  for (int off = 0; off < d; off += block) sum += baseValue(x + off, y + off, block);
  return sum;
}

double Kernel::valueAndGradientWrtY(const double* x, const double* y, int d, double* grad) const {
  if (block <= 0) return baseValueAndGradient(x, y, d, grad);
  // Blocks are disjoint coordinates, so the gradient of the sum is the concatenation.
  double sum = 0.0;
  for (int off = 0; off < d; off += block)
    sum += baseValueAndGradient(x + off, y + off, block, grad + off);
  return sum;
}

void Kernel::gradientWrtY(const double* x, const double* y, int d, double* grad) const {
  valueAndGradientWrtY(x, y, d, grad);
}

}  // namespace svmp::svm
