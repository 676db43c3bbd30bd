// A trained binary SVM: F(q) = sum_i coef_i k(sv_i, q) + bias, coef_i = y_i alpha_i
// (thesis ch. 2.1, decision function of the dual solution; the planners' risk function is |F|).
//
// Thread-safety: a const BinaryModel may be evaluated from many threads concurrently (no scratch).
#pragma once

#include <Eigen/Core>

#include "svm/kernel.hpp"
#include "svm/smo_solver.hpp"

namespace svmp::svm {

class BinaryModel {
 public:
  BinaryModel() = default;
  BinaryModel(Eigen::MatrixXd support_vectors, Eigen::VectorXd coefficients, double bias,
              const Kernel& kernel);

  // Keeps the samples with alpha_i > 0. Throws std::invalid_argument on mismatched sizes.
  static BinaryModel fromSolution(const Eigen::MatrixXd& X, const Eigen::VectorXd& y,
                                  const SolverResult& solution, const Kernel& kernel);

  const Eigen::MatrixXd& supportVectors() const { return sv_; }  // d x m, one SV per column
  const Eigen::VectorXd& coefficients() const { return coef_; }
  double bias() const { return bias_; }
  const Kernel& kernel() const { return kernel_; }
  int dim() const { return static_cast<int>(sv_.rows()); }
  int numSupportVectors() const { return static_cast<int>(sv_.cols()); }

  double decision(const double* q) const;  // full sum over all support vectors
  // F(q) and dF/dq (grad[0..dim)) in one pass over the support vectors.
  double decisionAndGradient(const double* q, double* grad) const;

 private:
  Eigen::MatrixXd sv_;
  Eigen::VectorXd coef_;
  double bias_ = 0.0;
  Kernel kernel_;
};

}  // namespace svmp::svm
