#include "planners/class_colouring.hpp"

#include <algorithm>
#include <set>

#include <nanoflann.hpp>

#include "svm/column_cloud.hpp"

namespace svmp::planners {

namespace {

using svm::ColumnCloud;
using KdTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, ColumnCloud>, ColumnCloud,
                                                   -1, size_t>;

// Radius-search result set that only notes the other labels met, each once per own label (stamp[l]:
// the own label that last met l).
struct OtherLabels {
  double radius;  // squared
  const std::vector<int>& dense;
  int own;
  std::vector<int>& stamp;
  std::vector<int>& met;
  size_t size() const { return 0; }
  bool full() const { return true; }
  double worstDist() const { return radius; }
  bool addPoint(double, size_t j) {
    const int label = dense[j];
    if (label != own && stamp[label] != own) stamp[label] = own, met.push_back(label);
    return true;
  }
};

}  // namespace

std::map<int, int> colourClasses(const Eigen::MatrixXd& points, const std::vector<int>& labels,
                                 const Eigen::VectorXd& scale, double distance) {
  std::map<int, std::set<int>> adjacent;
  for (int label : labels) adjacent[label];
  std::vector<int> label_of;  // dense index -> label
  std::map<int, int> index_of;
  for (const auto& [label, none] : adjacent) index_of[label] = static_cast<int>(label_of.size()), label_of.push_back(label);
  std::vector<int> dense(labels.size());
  for (size_t i = 0; i < labels.size(); ++i) dense[i] = index_of[labels[i]];
  const Eigen::MatrixXd scaled = scale.asDiagonal() * points;
  const ColumnCloud cloud{&scaled};
  const KdTree tree(static_cast<int>(scaled.rows()), cloud, nanoflann::KDTreeSingleIndexAdaptorParams(16));
  std::vector<int> stamp(label_of.size(), -1);
  std::vector<int> met;
  for (Eigen::Index i = 0; i < scaled.cols(); ++i) {
    met.clear();
    // Samples come grouped by obstacle, so each pair is noted about once per label (the sets keep it
    // correct in any order).
    OtherLabels found{distance * distance, dense, dense[static_cast<size_t>(i)], stamp, met};
    tree.findNeighbors(found, scaled.col(i).data(), nanoflann::SearchParams(32, 0.0f, false));
    const int own = labels[static_cast<size_t>(i)];
    for (int other : met) {
      adjacent[own].insert(label_of[static_cast<size_t>(other)]);
      adjacent[label_of[static_cast<size_t>(other)]].insert(own);
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
