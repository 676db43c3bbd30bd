#pragma once
// k-nearest neighbours in the weighted joint metric (thesis eq. 4.3): a nanoflann k-d tree over the
// points scaled by sqrt(w_d), where the metric is Euclidean. Built once over a fixed set; queries are
// const and safe from many threads (each call owns its result buffers).
#include <Eigen/Core>
#include <memory>
#include <vector>

namespace svmp::planners {

class NearestNeighbors {
 public:
  NearestNeighbors(const std::vector<Eigen::VectorXd>& points, const Eigen::VectorXd& scale);
  ~NearestNeighbors();
  NearestNeighbors(NearestNeighbors&&) noexcept;
  NearestNeighbors& operator=(NearestNeighbors&&) noexcept;

  // Indices of the (up to) k nearest points, nearest first.
  std::vector<int> nearest(const Eigen::Ref<const Eigen::VectorXd>& q, int k) const;
  int size() const { return static_cast<int>(scaled_.cols()); }

 private:
  struct Tree;
  Eigen::MatrixXd scaled_;  // dim x n, column-major (one point per column)
  Eigen::VectorXd scale_;
  std::unique_ptr<Tree> tree_;
};

}  // namespace svmp::planners
