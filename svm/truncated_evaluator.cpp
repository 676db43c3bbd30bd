#include "svm/truncated_evaluator.hpp"

#include <cmath>
#include <nanoflann.hpp>
#include <stdexcept>

namespace svmp::svm {

namespace {

// nanoflann dataset adaptor over the columns of a d x m matrix.
struct ColumnCloud {
  const Eigen::MatrixXd* points;
  size_t kdtree_get_point_count() const { return static_cast<size_t>(points->cols()); }
  double kdtree_get_pt(size_t i, size_t k) const { return (*points)(k, i); }
  template <class Box>
  bool kdtree_get_bbox(Box&) const { return false; }
};

using KdTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, ColumnCloud>,
                                                   ColumnCloud, -1, size_t>;

// Result set that sums coef * exp(-gamma d^2) (and the gradient) as points arrive.
template <bool kWithGradient>
struct SumResultSet {
  const Eigen::MatrixXd& sv;
  const double* coef;
  const double* q;
  double neg_gamma;
  double radius;  // squared
  double sum = 0.0;
  double* grad = nullptr;
  int d = 0;

  size_t size() const { return 0; }
  bool full() const { return true; }
  double worstDist() const { return radius; }
  bool addPoint(double dist, size_t index) {
    const double term = coef[index] * expNonPositive(neg_gamma * dist);
    sum += term;
    if constexpr (kWithGradient) {
      const double* x = sv.col(static_cast<Eigen::Index>(index)).data();
      const double f = -2.0 * neg_gamma * term;
      for (int k = 0; k < d; ++k) grad[k] += f * (x[k] - q[k]);
    }
    return true;
  }
};

}  // namespace

// Heap-allocated so the adaptor's pointer to the points survives moves of the evaluator.
struct TruncatedRbfEvaluator::Tree {
  Eigen::MatrixXd points;
  ColumnCloud cloud;
  KdTree index;
  explicit Tree(const Eigen::MatrixXd& sv)
      : points(sv),
        cloud{&points},
        index(static_cast<int>(sv.rows()), cloud, nanoflann::KDTreeSingleIndexAdaptorParams(16)) {}
};

TruncatedRbfEvaluator::TruncatedRbfEvaluator(const BinaryModel& model)
    : dim_(model.dim()), coef_(model.coefficients()), bias_(model.bias()) {
  if (!model.kernel().isPlainRbf())
    throw std::invalid_argument(std::string("TruncatedRbfEvaluator: needs a plain RBF kernel, got ") +
                                kernelTypeName(model.kernel().type) +
                                (model.kernel().block > 0 ? " (block-sum)" : ""));
  gamma_ = model.kernel().gamma;
  squared_radius_ = 5.0 / gamma_;
  bound_ = coef_.cwiseAbs().sum() * std::exp(-5.0);
  if (model.numSupportVectors() > 0) tree_ = std::make_unique<Tree>(model.supportVectors());
}

TruncatedRbfEvaluator::~TruncatedRbfEvaluator() = default;
TruncatedRbfEvaluator::TruncatedRbfEvaluator(TruncatedRbfEvaluator&&) noexcept = default;
TruncatedRbfEvaluator& TruncatedRbfEvaluator::operator=(TruncatedRbfEvaluator&&) noexcept = default;

double TruncatedRbfEvaluator::decision(const double* q) const {
  if (!tree_) return bias_;
  SumResultSet<false> rs{tree_->points, coef_.data(), q, -gamma_, squared_radius_};
  tree_->index.findNeighbors(rs, q, nanoflann::SearchParams(32, 0.0f, false));
  return rs.sum + bias_;
}

double TruncatedRbfEvaluator::decisionAndGradient(const double* q, double* grad) const {
  const int d = dim();
  for (int k = 0; k < d; ++k) grad[k] = 0.0;
  if (!tree_) return bias_;
  SumResultSet<true> rs{tree_->points, coef_.data(), q, -gamma_, squared_radius_};
  rs.grad = grad;
  rs.d = d;
  tree_->index.findNeighbors(rs, q, nanoflann::SearchParams(32, 0.0f, false));
  return rs.sum + bias_;
}

}  // namespace svmp::svm
