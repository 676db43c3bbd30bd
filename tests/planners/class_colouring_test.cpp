// Class colouring (planners/class_colouring.hpp): adjacent obstacle classes get different colours,
// distant ones share, a chain alternates, and the colouring is proper on random layouts.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>

#include "planners/class_colouring.hpp"

namespace svmp::planners {
namespace {

// Samples of `count` unit-spaced squares along x (side 0.8, so neighbours are 0.2 apart), 25 each.
void addSquare(double x0, double y0, int label, Eigen::MatrixXd& points, std::vector<int>& labels) {
  const Eigen::Index first = points.cols();
  points.conservativeResize(2, first + 25);
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 5; ++j) {
      points.col(first + 5 * i + j) = Eigen::Vector2d(x0 + 0.2 * i, y0 + 0.2 * j);
      labels.push_back(label);
    }
}

TEST(ClassColouring, AChainAlternatesAndDistantClassesShare) {
  Eigen::MatrixXd points(2, 0);
  std::vector<int> labels;
  for (int k = 0; k < 6; ++k) addSquare(1.0 * k, 0, k + 1, points, labels);  // gaps of 0.2
  addSquare(0, 10, 7, points, labels);                                       // far from all
  const auto colour = colourClasses(points, labels, Eigen::Vector2d::Ones(), 0.5);
  ASSERT_EQ(colour.size(), 7u);
  for (int k = 1; k < 6; ++k) EXPECT_NE(colour.at(k), colour.at(k + 1)) << "neighbours " << k << ", " << k + 1;
  int most = 0;
  for (const auto& [label, c] : colour) most = std::max(most, c);
  EXPECT_EQ(most, 2);          // a path graph needs two colours
  EXPECT_EQ(colour.at(7), 1);  // isolated: the first colour
  // With a threshold below the gaps nothing is adjacent: one colour for all.
  for (const auto& [label, c] : colourClasses(points, labels, Eigen::Vector2d::Ones(), 0.1)) EXPECT_EQ(c, 1);
}

TEST(ClassColouring, RandomLayoutsAreProperlyColoured) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0, 20);
  Eigen::MatrixXd points(2, 0);
  std::vector<int> labels;
  for (int k = 0; k < 60; ++k) addSquare(u(rng), u(rng), k + 1, points, labels);
  const double d = 0.5;
  const auto colour = colourClasses(points, labels, Eigen::Vector2d(1, 2), d);
  // Brute force: any two samples of different classes within d (weighted) must differ in colour.
  const Eigen::Vector2d scale(1, 2);
  int colours = 0;
  for (Eigen::Index i = 0; i < points.cols(); ++i) {
    colours = std::max(colours, colour.at(labels[i]));
    for (Eigen::Index j = i + 1; j < points.cols(); ++j)
      if (labels[i] != labels[j] && (points.col(i) - points.col(j)).cwiseProduct(scale).norm() < d * 0.999) {
        ASSERT_NE(colour.at(labels[i]), colour.at(labels[j])) << labels[i] << " and " << labels[j];
      }
  }
  EXPECT_LT(colours, 10);  // 60 classes, few colours

  // The same greedy colouring on the brute-force adjacency gives the same colours: the k-d tree's
  // radius searches neither miss nor invent a close pair.
  std::map<int, std::set<int>> adjacent;
  for (int label : labels) adjacent[label];
  for (Eigen::Index i = 0; i < points.cols(); ++i)
    for (Eigen::Index j = 0; j < points.cols(); ++j)
      if (labels[i] != labels[j] && (points.col(i) - points.col(j)).cwiseProduct(scale).squaredNorm() < d * d)
        adjacent[labels[i]].insert(labels[j]);
  std::vector<int> order;
  for (const auto& [label, next] : adjacent) order.push_back(label);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return adjacent[a].size() > adjacent[b].size(); });
  std::map<int, int> expected;
  for (int label : order) {
    std::set<int> taken;
    for (int other : adjacent[label])
      if (expected.count(other)) taken.insert(expected[other]);
    int c = 1;
    while (taken.count(c)) ++c;
    expected[label] = c;
  }
  EXPECT_EQ(colour, expected);
}

}  // namespace
}  // namespace svmp::planners
