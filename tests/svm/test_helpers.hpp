// Brute-force references for the SVM tests (exact double kernel, no cache, no shrinking).
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <limits>

#include "svm/kernel.hpp"

namespace svmp::svm::testing {

// G = Q alpha - e computed exactly over the support vectors.
inline Eigen::VectorXd exactGradient(const Eigen::MatrixXd& X, const Eigen::VectorXd& y,
                                     const Eigen::VectorXd& alpha, const Kernel& k) {
  const int d = static_cast<int>(X.rows());
  Eigen::VectorXd G = -Eigen::VectorXd::Ones(X.cols());
  for (Eigen::Index j = 0; j < X.cols(); ++j) {
    if (alpha[j] == 0) continue;
    const double w = y[j] * alpha[j];
    for (Eigen::Index i = 0; i < X.cols(); ++i)
      G[i] += y[i] * w * k.value(X.col(j).data(), X.col(i).data(), d);
  }
  return G;
}

// 0.5 a'Qa - e'a from an exact gradient.
inline double exactObjective(const Eigen::VectorXd& alpha, const Eigen::VectorXd& G) {
  return 0.5 * alpha.dot(G - Eigen::VectorXd::Ones(alpha.size()));
}

// Maximal violating pair gap m(alpha) - M(alpha) (0 at an exact optimum).
inline double kktViolation(const Eigen::VectorXd& y, const Eigen::VectorXd& C,
                           const Eigen::VectorXd& alpha, const Eigen::VectorXd& G) {
  double up = -std::numeric_limits<double>::infinity(), low = up;
  for (Eigen::Index t = 0; t < y.size(); ++t) {
    const bool upper = alpha[t] >= C[t], lower = alpha[t] <= 0;
    const bool in_up = y[t] > 0 ? !upper : !lower;
    const bool in_low = y[t] > 0 ? !lower : !upper;
    if (in_up) up = std::max(up, -y[t] * G[t]);
    if (in_low) low = std::max(low, y[t] * G[t]);
  }
  return up + low;
}

}  // namespace svmp::svm::testing
