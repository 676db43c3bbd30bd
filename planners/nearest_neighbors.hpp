#pragma once
// k-nearest neighbours in the weighted joint metric (thesis eq. 4.3): a nanoflann k-d tree over the
// points scaled by sqrt(w_d), where the metric is Euclidean. Built over a set that may grow at its end
// (extend); queries are const and safe from many threads (each call owns its result buffers).
#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <type_traits>
#include <unordered_map>
#include <vector>

#include "cspace/configuration_space.hpp"

namespace svmp::planners {

// Calls f(std::integral_constant<int, D>{}) with D = dim for 2 to 7 dimensions (the point robots and
// the arms), D = -1 (Eigen::Dynamic, nanoflann's dynamic size) otherwise: a scan or a k-d tree whose
// dimension is fixed at compile time unrolls its distances.
template <class F>
decltype(auto) withFixedDimension(int dim, F&& f) {
  switch (dim) {
    case 2: return f(std::integral_constant<int, 2>{});
    case 3: return f(std::integral_constant<int, 3>{});
    case 4: return f(std::integral_constant<int, 4>{});
    case 5: return f(std::integral_constant<int, 5>{});
    case 6: return f(std::integral_constant<int, 6>{});
    case 7: return f(std::integral_constant<int, 7>{});
    default: return f(std::integral_constant<int, -1>{});
  }
}

class NearestNeighbors {
 public:
  NearestNeighbors(const std::vector<Eigen::VectorXd>& points, const Eigen::VectorXd& scale);
  ~NearestNeighbors();
  NearestNeighbors(NearestNeighbors&&) noexcept;
  NearestNeighbors& operator=(NearestNeighbors&&) noexcept;

  // Adds points[size(), points.size()): the caller's set has grown at its end (a roadmap's nodes).
  // The new points are scanned by every query until they outnumber an eighth of the indexed ones;
  // then the tree is built again over all. Answers are the same as a new tree's (both exact; among
  // points exactly as near, the order may differ). A long SVMP repair rebuilt its tree twice a round
  // over 10-20k nodes to add a few hundred.
  void extend(const std::vector<Eigen::VectorXd>& points);

  // Indices of the (up to) k nearest points, nearest first.
  std::vector<int> nearest(const Eigen::Ref<const Eigen::VectorXd>& q, int k) const;
  // The index of the nearest point at most `radius` away, or -1: the search skips every cell beyond
  // the radius, so a far query costs little.
  int nearestWithin(const Eigen::Ref<const Eigen::VectorXd>& q, double radius) const;
  int size() const { return static_cast<int>(scaled_.cols() + tail_.cols()); }

  struct Tree;  // the k-d tree, of a fixed dimension where it can be (nearest_neighbors.cpp)

 private:
  void build();

  Eigen::MatrixXd scaled_;  // the indexed points, dim x n, column-major (one point per column)
  Eigen::MatrixXd tail_;    // the points added since, indices scaled_.cols() onwards
  Eigen::VectorXd scale_;
  std::unique_ptr<Tree> tree_;
};

// Points kept in order, each only when no kept point lies closer than `radius` in the weighted
// metric (SVMP's milestones: near-duplicate descent ends are dropped). Exact, without scanning every
// kept point: points are bucketed on a grid of cell `radius` over the space's two widest coordinates,
// and a point within radius of another lies in one of the 3 x 3 cells around it (the scan over all
// kept points was 5% of svmp's time on Fig 4.10: 1,000+ descent ends against ~300 kept). Radius 0
// keeps every point. Not thread-safe.
class NearDuplicateFilter {
 public:
  // `capacity`: how many points may be kept at most.
  NearDuplicateFilter(const cspace::ConfigurationSpace& space, double radius, int capacity);
  void add(const Eigen::VectorXd& q);
  // Adds q and returns true unless a kept point lies closer than the radius.
  bool addUnlessNear(const Eigen::VectorXd& q);

 private:
  std::pair<std::int64_t, std::int64_t> cellOf(const Eigen::VectorXd& x) const;
  void insert(const Eigen::VectorXd& x);

  Eigen::VectorXd scale_;
  double r2_, cell_;
  Eigen::MatrixXd points_;  // scaled, one per column
  int count_ = 0;
  int axes_[2] = {0, 0};
  std::unordered_map<std::uint64_t, std::vector<int>> buckets_;  // distinct cells may share a key
};

}  // namespace svmp::planners
