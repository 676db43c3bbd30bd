#include "svm/truncated_evaluator.hpp"

#include "svm/column_cloud.hpp"
#include "svm/simd_loops.hpp"

#include <algorithm>
#include <cmath>
#include <nanoflann.hpp>
#include <numeric>
#include <stdexcept>
#include <vector>

namespace svmp::svm {

namespace {

using KdTree =
    nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, ColumnCloud>,
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

struct TruncatedRbfEvaluator::Blocks {
  // Leaf size: in the plane leaves of 32 prune well; from d = 4 on a leaf's box spans most of the
  // truncation radius anyway and fewer, larger leaves cost less per query (d = 6, n = 20,000:
  // 2.01 / 1.80 / 1.86 / 1.99 us with leaves of 32 / 64 / 128 / 256; d = 2: 16 and 32 equal).
  int block;
  std::vector<double> xs, coef, lo, hi, centre, radius;
  loops::BlockedSupportVectors view{};

  Blocks(const Eigen::MatrixXd& sv, const Eigen::VectorXd& c) : block(sv.rows() <= 3 ? 32 : 64) {
    const int d = static_cast<int>(sv.rows()), m = static_cast<int>(sv.cols());
    std::vector<int> order(m);
    std::iota(order.begin(), order.end(), 0);
    std::vector<std::pair<int, int>> leaves;
    split(sv, order, 0, m, leaves);
    const int blocks = static_cast<int>(leaves.size());
    const long stride = static_cast<long>(blocks) * block;
    xs.assign(static_cast<size_t>(d) * stride, 0.0);
    coef.assign(stride, 0.0);
    lo.assign(static_cast<size_t>(d) * blocks, 0.0);
    hi.assign(static_cast<size_t>(d) * blocks, 0.0);
    for (int b = 0; b < blocks; ++b) {
      const auto [begin, end] = leaves[b];
      for (int slot = 0; slot < block; ++slot) {
        // padding repeats the leaf's first point with coefficient 0
        const int src = order[slot < end - begin ? begin + slot : begin];
        const long col = static_cast<long>(b) * block + slot;
        for (int k = 0; k < d; ++k) xs[k * stride + col] = sv(k, src);
        coef[col] = slot < end - begin ? c[src] : 0.0;
      }
      for (int k = 0; k < d; ++k) {
        double l = sv(k, order[begin]), h = l;
        for (int i = begin; i < end; ++i) {
          l = std::min(l, sv(k, order[i]));
          h = std::max(h, sv(k, order[i]));
        }
        lo[static_cast<size_t>(k) * blocks + b] = l;
        hi[static_cast<size_t>(k) * blocks + b] = h;
      }
    }
    centre.assign(static_cast<size_t>(d) * blocks, 0.0);
    radius.assign(blocks, 0.0);
    for (int b = 0; b < blocks; ++b) {
      for (int k = 0; k < d; ++k) {
        const size_t at = static_cast<size_t>(k) * blocks + b;
        centre[at] = 0.5 * (lo[at] + hi[at]);
      }
      double r2 = 0.0;
      for (int i = leaves[b].first; i < leaves[b].second; ++i) {
        double dist = 0.0;
        for (int k = 0; k < d; ++k) {
          const double c = sv(k, order[i]) - centre[static_cast<size_t>(k) * blocks + b];
          dist += c * c;
        }
        r2 = std::max(r2, dist);
      }
      radius[b] = std::sqrt(r2) * (1 + 1e-12);
    }
    view = {d,           blocks,    block,    stride,        xs.data(),
            coef.data(), lo.data(), hi.data(), centre.data(), radius.data()};
  }

  // Median split on the widest coordinate, at a multiple of block so leaves are full.
  void split(const Eigen::MatrixXd& sv, std::vector<int>& order, int begin, int end,
             std::vector<std::pair<int, int>>& leaves) const {
    if (end - begin <= block) {
      leaves.emplace_back(begin, end);
      return;
    }
    int widest = 0;
    double spread = -1;
    for (int k = 0; k < sv.rows(); ++k) {
      double l = sv(k, order[begin]), h = l;
      for (int i = begin; i < end; ++i) {
        l = std::min(l, sv(k, order[i]));
        h = std::max(h, sv(k, order[i]));
      }
      if (h - l > spread) {
        spread = h - l;
        widest = k;
      }
    }
    const int mid = begin + ((end - begin) / 2 + block - 1) / block * block;
    std::nth_element(order.begin() + begin, order.begin() + mid, order.begin() + end,
                     [&](int a, int b) { return sv(widest, a) < sv(widest, b); });
    split(sv, order, begin, mid, leaves);
    split(sv, order, mid, end, leaves);
  }
};

TruncatedRbfEvaluator::TruncatedRbfEvaluator(const BinaryModel& model)
    : dim_(model.dim()), coef_(model.coefficients()), bias_(model.bias()) {
  if (!model.kernel().isPlainRbf())
    throw std::invalid_argument(
        std::string("TruncatedRbfEvaluator: needs a plain RBF kernel, got ") +
        kernelTypeName(model.kernel().type) + (model.kernel().block > 0 ? " (block-sum)" : ""));
  gamma_ = model.kernel().gamma;
  squared_radius_ = 5.0 / gamma_;
  bound_ = coef_.cwiseAbs().sum() * std::exp(-5.0);
  if (model.numSupportVectors() == 0) return;
  if (dim_ <= 16)
    blocks_ = std::make_unique<Blocks>(model.supportVectors(), coef_);
  else
    tree_ = std::make_unique<Tree>(model.supportVectors());
}

TruncatedRbfEvaluator::~TruncatedRbfEvaluator() = default;
TruncatedRbfEvaluator::TruncatedRbfEvaluator(TruncatedRbfEvaluator&&) noexcept = default;
TruncatedRbfEvaluator& TruncatedRbfEvaluator::operator=(TruncatedRbfEvaluator&&) noexcept = default;

double TruncatedRbfEvaluator::sum(const double* q, double* grad, double squared_radius) const {
  const int d = dim();
  if (grad)
    for (int k = 0; k < d; ++k) grad[k] = 0.0;
  if (blocks_) return bias_ + loops::truncatedRbfSum(blocks_->view, q, gamma_, squared_radius, grad);
  if (!tree_) return bias_;
  if (!grad) {
    SumResultSet<false> rs{tree_->points, coef_.data(), q, -gamma_, squared_radius};
    tree_->index.findNeighbors(rs, q, nanoflann::SearchParams(32, 0.0f, false));
    return rs.sum + bias_;
  }
  SumResultSet<true> rs{tree_->points, coef_.data(), q, -gamma_, squared_radius};
  rs.grad = grad;
  rs.d = d;
  tree_->index.findNeighbors(rs, q, nanoflann::SearchParams(32, 0.0f, false));
  return rs.sum + bias_;
}

double TruncatedRbfEvaluator::decision(const double* q) const { return sum(q, nullptr, squared_radius_); }

double TruncatedRbfEvaluator::decisionAndGradient(const double* q, double* grad) const {
  return sum(q, grad, squared_radius_);
}

double TruncatedRbfEvaluator::exactDecision(const double* q) const {
  return sum(q, nullptr, kExactCutoff / gamma_);
}

double TruncatedRbfEvaluator::exactDecisionAndGradient(const double* q, double* grad) const {
  return sum(q, grad, kExactCutoff / gamma_);
}

}  // namespace svmp::svm
