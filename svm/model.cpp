#include "svm/model.hpp"

#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

namespace svmp::svm {

BinaryModel::BinaryModel(Eigen::MatrixXd support_vectors, Eigen::VectorXd coefficients, double bias,
                         const Kernel& kernel)
    : sv_(std::move(support_vectors)),
      coef_(std::move(coefficients)),
      bias_(bias),
      kernel_(kernel) {
  if (sv_.cols() != coef_.size()) {
    std::ostringstream msg;
    msg << "BinaryModel: " << sv_.cols() << " support vectors but " << coef_.size()
        << " coefficients";
    throw std::invalid_argument(msg.str());
  }
}

BinaryModel BinaryModel::fromSolution(const Eigen::MatrixXd& X, const Eigen::VectorXd& y,
                                      const SolverResult& solution, const Kernel& kernel) {
  if (y.size() != X.cols() || solution.alpha.size() != X.cols()) {
    std::ostringstream msg;
    msg << "BinaryModel::fromSolution: X has " << X.cols() << " samples, y " << y.size()
        << ", alpha " << solution.alpha.size();
    throw std::invalid_argument(msg.str());
  }
  Eigen::Index m = 0;
  for (Eigen::Index i = 0; i < X.cols(); ++i) m += solution.alpha[i] > 0;
  Eigen::MatrixXd sv(X.rows(), m);
  Eigen::VectorXd coef(m);
  for (Eigen::Index i = 0, s = 0; i < X.cols(); ++i) {
    if (!(solution.alpha[i] > 0)) continue;
    sv.col(s) = X.col(i);
    coef[s++] = y[i] * solution.alpha[i];
  }
  return BinaryModel(std::move(sv), std::move(coef), solution.bias, kernel);
}

double BinaryModel::decision(const double* q) const {
  const int d = dim();
  double f = bias_;
  if (kernel_.isPlainRbf()) {
    for (int s = 0; s < numSupportVectors(); ++s) {
      const double* x = sv_.col(s).data();
      double dist = 0.0;
      for (int k = 0; k < d; ++k) dist += (x[k] - q[k]) * (x[k] - q[k]);
      f += coef_[s] * expNonPositive(-kernel_.gamma * dist);
    }
    return f;
  }
  for (int s = 0; s < numSupportVectors(); ++s)
    f += coef_[s] * kernel_.value(sv_.col(s).data(), q, d);
  return f;
}

double BinaryModel::decisionAndGradient(const double* q, double* grad) const {
  const int d = dim();
  double f = bias_;
  for (int k = 0; k < d; ++k) grad[k] = 0.0;
  if (kernel_.isPlainRbf()) {
    const double g2 = 2.0 * kernel_.gamma;
    for (int s = 0; s < numSupportVectors(); ++s) {
      const double* x = sv_.col(s).data();
      double dist = 0.0;
      for (int k = 0; k < d; ++k) dist += (x[k] - q[k]) * (x[k] - q[k]);
      const double exponent = -kernel_.gamma * dist;
      // expNonPositive holds its argument at -700 (e^-700 = 1e-304); beyond, the term and its
      // gradient are zero to double precision, where 2 gamma e^-700 is not for a gamma of 1e300.
      if (exponent < -700) continue;
      const double term = coef_[s] * expNonPositive(exponent);
      f += term;
      // d/dq exp(-gamma |x - q|^2) = 2 gamma (x - q) exp(...)
      for (int k = 0; k < d; ++k) grad[k] += g2 * term * (x[k] - q[k]);
    }
    return f;
  }
  double small[64];
  std::vector<double> big;
  double* g = small;
  if (d > 64) {
    big.resize(d);
    g = big.data();
  }
  for (int s = 0; s < numSupportVectors(); ++s) {
    f += coef_[s] * kernel_.valueAndGradientWrtY(sv_.col(s).data(), q, d, g);
    for (int k = 0; k < d; ++k) grad[k] += coef_[s] * g[k];
  }
  return f;
}

}  // namespace svmp::svm
