#include "planners/nearest_neighbors.hpp"

#include <nanoflann.hpp>

#include "svm/column_cloud.hpp"

namespace svmp::planners {

using svm::ColumnCloud;

struct NearestNeighbors::Tree {
  using Index = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Adaptor<double, ColumnCloud>,
                                                    ColumnCloud, -1, size_t>;
  ColumnCloud cloud;
  Index index;
  Tree(const Eigen::MatrixXd* pts, int dim)
      : cloud{pts}, index(dim, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10)) {
    index.buildIndex();
  }
};

NearestNeighbors::NearestNeighbors(const std::vector<Eigen::VectorXd>& points,
                                   const Eigen::VectorXd& scale)
    : scale_(scale) {
  scaled_.resize(scale.size(), static_cast<Eigen::Index>(points.size()));
  for (size_t i = 0; i < points.size(); ++i) scaled_.col(i) = points[i].cwiseProduct(scale);
  if (!points.empty()) tree_ = std::make_unique<Tree>(&scaled_, static_cast<int>(scale.size()));
}

NearestNeighbors::~NearestNeighbors() = default;
NearestNeighbors::NearestNeighbors(NearestNeighbors&& other) noexcept
    : scaled_(std::move(other.scaled_)), scale_(std::move(other.scale_)), tree_(std::move(other.tree_)) {
  if (tree_) tree_->cloud.points = &scaled_;
}
NearestNeighbors& NearestNeighbors::operator=(NearestNeighbors&& other) noexcept {
  scaled_ = std::move(other.scaled_);
  scale_ = std::move(other.scale_);
  tree_ = std::move(other.tree_);
  if (tree_) tree_->cloud.points = &scaled_;
  return *this;
}

std::vector<int> NearestNeighbors::nearest(const Eigen::Ref<const Eigen::VectorXd>& q, int k) const {
  if (!tree_ || k <= 0) return {};
  const size_t n = std::min<size_t>(static_cast<size_t>(k), static_cast<size_t>(size()));
  const Eigen::VectorXd x = q.cwiseProduct(scale_);
  std::vector<size_t> index(n);
  std::vector<double> dist(n);
  const size_t found = tree_->index.knnSearch(x.data(), n, index.data(), dist.data());
  return std::vector<int>(index.begin(), index.begin() + found);
}

}  // namespace svmp::planners
