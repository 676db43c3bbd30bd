#include "planners/class_colouring.hpp"

#include <algorithm>

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
  // Dense indices in label order; adjacency as sorted vectors of dense indices (a map of sets cost
  // most of forest_200's 1.5 ms of colouring in allocations).
  std::vector<int> label_of(labels.begin(), labels.end());
  std::sort(label_of.begin(), label_of.end());
  label_of.erase(std::unique(label_of.begin(), label_of.end()), label_of.end());
  const int classes = static_cast<int>(label_of.size());
  std::vector<int> dense(labels.size());
  for (size_t i = 0; i < labels.size(); ++i)
    dense[i] = static_cast<int>(std::lower_bound(label_of.begin(), label_of.end(), labels[i]) - label_of.begin());
  const Eigen::MatrixXd scaled = scale.asDiagonal() * points;
  const ColumnCloud cloud{&scaled};
  const KdTree tree(static_cast<int>(scaled.rows()), cloud, nanoflann::KDTreeSingleIndexAdaptorParams(16));
  std::vector<int> stamp(label_of.size(), -1);
  std::vector<int> met;
  std::vector<std::vector<int>> adjacent(classes);
  for (Eigen::Index i = 0; i < scaled.cols(); ++i) {
    met.clear();
    // Samples come grouped by obstacle, so each pair is noted about once per label (the sort below
    // keeps it correct in any order). A pair is met from both sides (the distance is symmetric), so
    // each side notes only the labels above its own.
    const int own = dense[static_cast<size_t>(i)];
    OtherLabels found{distance * distance, dense, own, stamp, met};
    tree.findNeighbors(found, scaled.col(i).data(), nanoflann::SearchParams(32, 0.0f, false));
    for (int other : met)
      if (other > own) adjacent[own].push_back(other), adjacent[other].push_back(own);
  }
  // Each list sorted on its own: 2,250 obstacles of tinydust2d met 720k pairs, whose one global sort
  // took most of the colouring.
  for (std::vector<int>& a : adjacent) {
    std::sort(a.begin(), a.end());
    a.erase(std::unique(a.begin(), a.end()), a.end());
  }
  std::vector<int> order(classes);
  for (int c = 0; c < classes; ++c) order[c] = c;
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return adjacent[a].size() > adjacent[b].size(); });
  std::vector<int> colour(classes, 0);
  std::vector<char> taken;
  for (int c : order) {
    taken.assign(adjacent[c].size() + 2, 0);  // some colour in 1..degree + 1 is free
    for (int other : adjacent[c])
      if (colour[other] < static_cast<int>(taken.size())) taken[colour[other]] = 1;
    int pick = 1;
    while (taken[pick]) ++pick;
    colour[c] = pick;
  }
  std::map<int, int> out;
  for (int c = 0; c < classes; ++c) out[label_of[c]] = colour[c];
  return out;
}

}  // namespace svmp::planners
