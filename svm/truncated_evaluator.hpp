// Truncated evaluation of an RBF decision function (thesis ch. 4.3.1): terms whose kernel value
// exp(-gamma d^2) is below exp(-5) are treated as zero. A k-d tree (nanoflann) over the support
// vectors finds the terms with SQUARED distance d^2 < 5/gamma; the sum and its gradient are
// accumulated inside the search's result set, so nothing is allocated per term.
//
// The truncated F differs from the full sum by at most truncationBound() = sum_i |coef_i| exp(-5).
// Thread-safety: decision() and decisionAndGradient() are const and keep all scratch on the stack
// (nanoflann's search is const); any number of threads may evaluate one evaluator concurrently.
#pragma once

#include <Eigen/Core>
#include <memory>

#include "svm/model.hpp"

namespace svmp::svm {

class TruncatedRbfEvaluator {
 public:
  // Copies the support vectors; the model may be destroyed afterwards. Throws std::invalid_argument
  // if the kernel is not a plain RBF kernel.
  explicit TruncatedRbfEvaluator(const BinaryModel& model);
  ~TruncatedRbfEvaluator();
  TruncatedRbfEvaluator(TruncatedRbfEvaluator&&) noexcept;
  TruncatedRbfEvaluator& operator=(TruncatedRbfEvaluator&&) noexcept;

  double decision(const double* q) const;
  double decisionAndGradient(const double* q, double* grad) const;

  double truncationBound() const { return bound_; }
  double squaredRadius() const { return squared_radius_; }  // 5 / gamma
  int dim() const { return dim_; }
  double bias() const { return bias_; }

 private:
  struct Tree;
  int dim_ = 0;
  Eigen::VectorXd coef_;
  double bias_ = 0.0;
  double gamma_ = 1.0;
  double squared_radius_ = 5.0;
  double bound_ = 0.0;
  std::unique_ptr<Tree> tree_;
};

}  // namespace svmp::svm
