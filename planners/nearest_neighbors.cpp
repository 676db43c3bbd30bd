#include "planners/nearest_neighbors.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <nanoflann.hpp>

#include "svm/column_cloud.hpp"

namespace svmp::planners {

using svm::ColumnCloud;

// The index over `cloud`, its dimension fixed at compile time where withFixedDimension fixes it
// (nanoflann then also keeps a search's per-dimension distances on the stack, not in a vector
// allocated per search).
struct NearestNeighbors::Tree {
  ColumnCloud cloud;
  explicit Tree(const Eigen::MatrixXd* pts) : cloud{pts} {}
  virtual ~Tree() = default;
  virtual size_t knn(const double* x, size_t n, size_t* index, double* dist) const = 0;
  virtual int nearestWithin(const double* x, double radius2) const = 0;
};

namespace {

template <int D>
struct TreeOf final : NearestNeighbors::Tree {
  using Index = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Adaptor<double, ColumnCloud>, ColumnCloud, D, size_t>;
  Index index;
  TreeOf(const Eigen::MatrixXd* pts, int dim)
      : Tree(pts), index(dim, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10)) {
    index.buildIndex();
  }
  size_t knn(const double* x, size_t n, size_t* out, double* dist) const override {
    return index.knnSearch(x, n, out, dist);
  }
  int nearestWithin(const double* x, double radius2) const override {
    nanoflann::KNNResultSet<double, size_t, size_t> result(1);
    size_t out = 0;
    double dist = 0;
    result.init(&out, &dist);
    dist = radius2;  // the result's worst distance: the search prunes every cell beyond it
    index.findNeighbors(result, x, nanoflann::SearchParams());
    return result.size() == 1 ? static_cast<int>(out) : -1;
  }
};

std::unique_ptr<NearestNeighbors::Tree> makeTree(const Eigen::MatrixXd* pts, int dim) {
  return withFixedDimension(dim, [&](auto d) -> std::unique_ptr<NearestNeighbors::Tree> {
    return std::make_unique<TreeOf<decltype(d)::value>>(pts, dim);
  });
}

}  // namespace

NearestNeighbors::NearestNeighbors(const std::vector<Eigen::VectorXd>& points,
                                   const Eigen::VectorXd& scale)
    : tail_(scale.size(), 0), scale_(scale) {
  scaled_.resize(scale.size(), static_cast<Eigen::Index>(points.size()));
  for (size_t i = 0; i < points.size(); ++i) scaled_.col(i) = points[i].cwiseProduct(scale);
  build();
}

NearestNeighbors::~NearestNeighbors() = default;
NearestNeighbors::NearestNeighbors(NearestNeighbors&& other) noexcept
    : scaled_(std::move(other.scaled_)),
      tail_(std::move(other.tail_)),
      scale_(std::move(other.scale_)),
      tree_(std::move(other.tree_)) {
  if (tree_) tree_->cloud.points = &scaled_;
}
NearestNeighbors& NearestNeighbors::operator=(NearestNeighbors&& other) noexcept {
  scaled_ = std::move(other.scaled_);
  tail_ = std::move(other.tail_);
  scale_ = std::move(other.scale_);
  tree_ = std::move(other.tree_);
  if (tree_) tree_->cloud.points = &scaled_;
  return *this;
}

void NearestNeighbors::build() {
  tree_.reset();
  if (scaled_.cols() > 0) tree_ = makeTree(&scaled_, static_cast<int>(scale_.size()));
}

void NearestNeighbors::extend(const std::vector<Eigen::VectorXd>& points) {
  const Eigen::Index old_size = size(), added = static_cast<Eigen::Index>(points.size()) - old_size;
  if (added <= 0) return;
  const Eigen::Index first = tail_.cols();
  tail_.conservativeResize(Eigen::NoChange, first + added);
  for (Eigen::Index i = 0; i < added; ++i) tail_.col(first + i) = points[old_size + i].cwiseProduct(scale_);
  if (tail_.cols() * 8 <= scaled_.cols()) return;
  Eigen::MatrixXd all(scaled_.rows(), scaled_.cols() + tail_.cols());
  all << scaled_, tail_;
  scaled_ = std::move(all);
  tail_.resize(scale_.size(), 0);
  build();
}

std::vector<int> NearestNeighbors::nearest(const Eigen::Ref<const Eigen::VectorXd>& q, int k) const {
  if (size() == 0 || k <= 0) return {};
  const Eigen::VectorXd x = q.cwiseProduct(scale_);
  const size_t n = std::min<size_t>(static_cast<size_t>(k), static_cast<size_t>(scaled_.cols()));
  std::vector<size_t> index(n);
  std::vector<double> dist(n);
  const size_t found = tree_ ? tree_->knn(x.data(), n, index.data(), dist.data()) : 0;
  if (tail_.cols() == 0) return std::vector<int>(index.begin(), index.begin() + found);
  std::vector<std::pair<double, int>> all;  // (squared distance, index)
  for (size_t i = 0; i < found; ++i) all.emplace_back(dist[i], static_cast<int>(index[i]));
  for (Eigen::Index t = 0; t < tail_.cols(); ++t)
    all.emplace_back((tail_.col(t) - x).squaredNorm(), static_cast<int>(scaled_.cols() + t));
  const size_t keep = std::min(all.size(), static_cast<size_t>(k));
  std::partial_sort(all.begin(), all.begin() + keep, all.end());
  std::vector<int> out(keep);
  for (size_t i = 0; i < keep; ++i) out[i] = all[i].second;
  return out;
}

int NearestNeighbors::nearestWithin(const Eigen::Ref<const Eigen::VectorXd>& q, double radius) const {
  if (size() == 0 || !(radius >= 0)) return -1;
  const Eigen::VectorXd x = q.cwiseProduct(scale_);
  // The search keeps points strictly closer than its bound: one step above radius^2 keeps those at it.
  double bound = std::nextafter(radius * radius, std::numeric_limits<double>::infinity());
  int best = tree_ ? tree_->nearestWithin(x.data(), bound) : -1;
  if (best >= 0) bound = (scaled_.col(best) - x).squaredNorm();
  for (Eigen::Index t = 0; t < tail_.cols(); ++t)
    if (const double d = (tail_.col(t) - x).squaredNorm(); d < bound)
      best = static_cast<int>(scaled_.cols() + t), bound = d;
  return best;
}

namespace {
std::uint64_t cellKey(std::int64_t i, std::int64_t j) {
  return static_cast<std::uint64_t>(i) * 0x9E3779B97F4A7C15ull + static_cast<std::uint64_t>(j);
}
}  // namespace

NearDuplicateFilter::NearDuplicateFilter(const cspace::ConfigurationSpace& space, double radius, int capacity)
    : scale_(space.metricScale()), r2_(radius * radius), cell_(radius), points_(scale_.size(), capacity) {
  const Eigen::VectorXd range = (space.upper() - space.lower()).cwiseProduct(scale_);
  for (int d = 0; d < range.size(); ++d)
    if (range[d] > range[axes_[0]]) axes_[0] = d;
  axes_[1] = axes_[0] == 0 && range.size() > 1 ? 1 : 0;
  for (int d = 0; d < range.size(); ++d)
    if (d != axes_[0] && range[d] > range[axes_[1]]) axes_[1] = d;
}

void NearDuplicateFilter::add(const Eigen::VectorXd& q) { insert(q.cwiseProduct(scale_)); }

bool NearDuplicateFilter::addUnlessNear(const Eigen::VectorXd& q) {
  if (!(r2_ > 0)) return true;
  const Eigen::VectorXd x = q.cwiseProduct(scale_);
  const auto [c0, c1] = cellOf(x);
  for (std::int64_t i = c0 - 1; i <= c0 + 1; ++i)
    for (std::int64_t j = c1 - 1; j <= c1 + 1; ++j) {
      const auto bucket = buckets_.find(cellKey(i, j));
      if (bucket == buckets_.end()) continue;
      for (const int p : bucket->second)
        if ((points_.col(p) - x).squaredNorm() < r2_) return false;
    }
  insert(x);
  return true;
}

std::pair<std::int64_t, std::int64_t> NearDuplicateFilter::cellOf(const Eigen::VectorXd& x) const {
  // Clamped: a radius far below the coordinates only merges far cells, which the exact test separates.
  auto cell = [&](double v) { return static_cast<std::int64_t>(std::floor(std::clamp(v / cell_, -1e15, 1e15))); };
  return {cell(x[axes_[0]]), cell(x[axes_[1]])};
}

void NearDuplicateFilter::insert(const Eigen::VectorXd& x) {
  if (!(r2_ > 0)) return;
  points_.col(count_) = x;
  const auto [c0, c1] = cellOf(x);
  buckets_[cellKey(c0, c1)].push_back(count_++);
}

}  // namespace svmp::planners
