#include "planners/class_colouring.hpp"

#include <algorithm>
#include <set>

#include "planners/nearest_neighbors.hpp"

namespace svmp::planners {

std::map<int, int> colourClasses(const Eigen::MatrixXd& points, const std::vector<int>& labels,
                                 const Eigen::VectorXd& scale, double distance, int neighbours) {
  std::map<int, std::set<int>> adjacent;
  for (int label : labels) adjacent[label];
  std::vector<Eigen::VectorXd> columns(points.cols());
  for (Eigen::Index i = 0; i < points.cols(); ++i) columns[i] = points.col(i);
  const NearestNeighbors nn(columns, scale);
  const double d2 = distance * distance;
  auto far = [&](Eigen::Index i, int j) { return (points.col(j) - points.col(i)).cwiseProduct(scale).squaredNorm() >= d2; };
  for (Eigen::Index i = 0; i < points.cols(); ++i) {
    // Every sample within `distance`: widen the k-nearest query until its farthest is beyond it.
    std::vector<int> near;
    for (int k = neighbours;; k *= 4) {
      near = nn.nearest(points.col(i), k);
      if (static_cast<int>(near.size()) < k || far(i, near.back())) break;
    }
    for (int j : near) {
      if (labels[j] == labels[i] || far(i, j)) continue;
      adjacent[labels[i]].insert(labels[j]);
      adjacent[labels[j]].insert(labels[i]);
    }
  }
  std::vector<int> order;
  for (const auto& [label, next] : adjacent) order.push_back(label);
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return adjacent[a].size() > adjacent[b].size(); });
  std::map<int, int> colour;
  for (int label : order) {
    std::set<int> taken;
    for (int other : adjacent[label])
      if (auto it = colour.find(other); it != colour.end()) taken.insert(it->second);
    int c = 1;
    while (taken.count(c)) ++c;
    colour[label] = c;
  }
  return colour;
}

}  // namespace svmp::planners
