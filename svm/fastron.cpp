#include "svm/fastron.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "svm/fastron_loops.hpp"
#include "svm/kernel_cache.hpp"

namespace svmp::svm {
namespace {

// 16 floats: the widest vector the query loop uses (AVX-512) reads whole vectors.
long paddedStride(int n) { return (static_cast<long>(n) + 15) / 16 * 16; }

// Row-major features to coordinate rows of `stride` floats (zero padded).
std::vector<float> toColumns(const std::vector<float>& rows, const std::vector<int>& pick, int dim,
                             long stride) {
  std::vector<float> out(static_cast<size_t>(dim) * stride, 0.f);
  for (size_t j = 0; j < pick.size(); ++j)
    for (int k = 0; k < dim; ++k) out[k * stride + j] = rows[static_cast<size_t>(pick[j]) * dim + k];
  return out;
}

}  // namespace

std::string FastronOptions::validate() const {
  std::ostringstream why;
  if (!(gamma > 0) || !std::isfinite(gamma)) why << "gamma must be positive and finite, got " << gamma;
  else if (!(beta > 0) || !std::isfinite(beta)) why << "beta must be positive and finite, got " << beta;
  else if (max_updates < 1) why << "max_updates must be at least 1, got " << max_updates;
  else if (max_support < 1) why << "max_support must be at least 1, got " << max_support;
  else if (!(cache_mb > 0) || !std::isfinite(cache_mb)) why << "cache_mb must be positive, got " << cache_mb;
  return why.str();
}

FastronModel::FastronModel(int dim, int block, FastronOptions options)
    : dim_(dim), block_(block), options_(options) {
  if (dim < 1 || block < 1 || dim % block != 0)
    throw std::invalid_argument("FastronModel: dimension " + std::to_string(dim) +
                                " is not a positive multiple of the block " + std::to_string(block));
  if (const std::string why = options_.validate(); !why.empty())
    throw std::invalid_argument("FastronModel: " + why);
}

FastronTrainStats FastronModel::train(const std::vector<float>& features,
                                      const std::vector<std::int8_t>& labels, std::vector<double>& alpha,
                                      const std::function<bool()>& stop) {
  const int n = static_cast<int>(labels.size());
  if (features.size() != static_cast<size_t>(n) * dim_ || alpha.size() != labels.size())
    throw std::invalid_argument("FastronModel::train: features, labels and weights differ in size");
  for (int j = 0; j < n; ++j) {
    if (labels[j] != 1 && labels[j] != -1)
      throw std::invalid_argument("FastronModel::train: label " + std::to_string(labels[j]) + " of point " +
                                  std::to_string(j) + " is not +1 or -1");
    if (!std::isfinite(alpha[j]))
      throw std::invalid_argument("FastronModel::train: weight of point " + std::to_string(j) + " is not finite");
  }
  for (float v : features)
    if (!std::isfinite(v)) throw std::invalid_argument("FastronModel::train: a feature is not finite");

  std::vector<int> all(n);
  for (int j = 0; j < n; ++j) all[j] = j;
  const long stride = paddedStride(n);
  const std::vector<float> X = toColumns(features, all, dim_, stride);
  const fastron_loops::PointsSoA points{X.data(), stride, dim_, block_, n};
  const float half_gamma = static_cast<float>(options_.gamma / 2);
  const double kii = dim_ / block_;  // k(x, x): one per block

  FastronTrainStats stats;
  KernelCache cache(std::max(n, 1), options_.cache_mb);
  auto column = [&](int i) -> const float* {
    int filled = 0;
    float* c = cache.request(i, n, &filled);
    if (filled < n) {
      fastron_loops::kernelColumn(points, &features[static_cast<size_t>(i) * dim_], half_gamma, c);
      ++stats.kernel_columns;
    }
    return c;
  };

  std::vector<double> F(n, 0.0);
  int support = 0;
  for (int i = 0; i < n; ++i) {
    if (alpha[i] == 0) continue;
    ++support;
    const float* c = column(i);
    for (int j = 0; j < n; ++j) F[j] += alpha[i] * c[j];
  }
  auto move = [&](int i, double delta) {
    const float* c = column(i);
    alpha[i] += delta;
    for (int j = 0; j < n; ++j) F[j] += delta * c[j];
  };

  while (stats.steps < options_.max_updates && n > 0) {
    if (stop && stop()) {
      stats.stopped = true;
      break;
    }
    int worst = 0;
    for (int j = 1; j < n; ++j)
      if (labels[j] * F[j] < labels[worst] * F[worst]) worst = j;
    if (labels[worst] * F[worst] <= 0 && (alpha[worst] != 0 || support < options_.max_support)) {
      const double target = labels[worst] > 0 ? options_.beta : -1.0;
      const bool is_new = alpha[worst] == 0;
      move(worst, (target - F[worst]) / kii);
      if (is_new) ++support, ++stats.added;
      else ++stats.adjusted;
      if (alpha[worst] == 0) --support;
      ++stats.steps;
      continue;
    }
    // A support point that keeps a positive margin without its own weight is redundant.
    int redundant = -1;
    double best = 0;
    for (int j = 0; j < n; ++j) {
      if (alpha[j] == 0) continue;
      const double m = labels[j] * (F[j] - alpha[j] * kii);
      if (m > best) best = m, redundant = j;
    }
    if (redundant < 0) break;
    move(redundant, -alpha[redundant]);
    alpha[redundant] = 0;
    --support, ++stats.removed, ++stats.steps;
  }
  stats.min_margin = std::numeric_limits<double>::infinity();
  for (int j = 0; j < n; ++j) stats.min_margin = std::min(stats.min_margin, labels[j] * F[j]);
  stats.converged = n == 0 || stats.min_margin > 0;
  storeSupport(features, alpha);
  stats.support = support_;
  return stats;
}

void FastronModel::storeSupport(const std::vector<float>& features, const std::vector<double>& alpha) {
  support_index_.clear();
  for (size_t j = 0; j < alpha.size(); ++j)
    if (alpha[j] != 0) support_index_.push_back(static_cast<int>(j));
  support_ = static_cast<int>(support_index_.size());
  stride_ = paddedStride(support_);
  coords_ = toColumns(features, support_index_, dim_, stride_);
  weights_.assign(stride_, 0.f);
  for (int j = 0; j < support_; ++j) weights_[j] = static_cast<float>(alpha[support_index_[j]]);
}

double FastronModel::value(const float* x) const {
  const fastron_loops::PointsSoA points{coords_.data(), stride_, dim_, block_, support_};
  return fastron_loops::weightedSum(points, weights_.data(), x, static_cast<float>(options_.gamma / 2));
}

}  // namespace svmp::svm
