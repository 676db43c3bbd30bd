#include "planners/hyperplane_labelling.hpp"

#include <cmath>
#include <map>
#include <random>
#include <stdexcept>

namespace svmp::planners {
namespace {

// A random unit normal orthogonal to d = goal - start, so the hyperplane contains both.
Eigen::VectorXd randomNormal(const Eigen::VectorXd& d, std::mt19937_64& rng) {
  std::normal_distribution<double> normal(0, 1);
  const Eigen::VectorXd u = d.normalized();
  for (;;) {
    Eigen::VectorXd w(d.size());
    for (int i = 0; i < w.size(); ++i) w[i] = normal(rng);
    w -= w.dot(u) * u;
    if (w.norm() > 1e-9) return w.normalized();
  }
}

struct RegionSides {
  std::map<int, double> sum;  // sum of sign(P) per region
  std::map<int, int> count;
};

RegionSides sides(const Eigen::MatrixXd& x, const std::vector<int>& regions, const Eigen::VectorXd& w,
                  double b) {
  RegionSides s;
  for (int i = 0; i < x.cols(); ++i) {
    s.sum[regions[i]] += (w.dot(x.col(i)) + b) >= 0 ? 1.0 : -1.0;
    s.count[regions[i]] += 1;
  }
  return s;
}

Labelling apply(const Eigen::MatrixXd& x, const std::vector<int>& regions, int boundary_region,
                const Eigen::VectorXd& w, double b, bool boundary_by_sample) {
  const RegionSides s = sides(x, regions, w, b);
  Labelling l{w, b, Eigen::VectorXd(x.cols()), false};
  for (int i = 0; i < x.cols(); ++i) {
    const bool own = boundary_by_sample && regions[i] == boundary_region;
    const double side = own ? w.dot(x.col(i)) + b : s.sum.at(regions[i]);
    l.y[i] = side >= 0 ? 1.0 : -1.0;
  }
  l.both_classes = (l.y.array() > 0).any() && (l.y.array() < 0).any();
  return l;
}

}  // namespace

Labelling labelByHyperplane(const Eigen::MatrixXd& samples, const std::vector<int>& regions,
                            int boundary_region, const Eigen::VectorXd& start, const Eigen::VectorXd& goal,
                            LabellingMethod method, std::uint64_t seed, int candidates) {
  if (samples.cols() == 0 || static_cast<int>(regions.size()) != samples.cols())
    throw std::invalid_argument("labelling: need one region per sample and at least one sample");
  const Eigen::VectorXd d = goal - start;
  if (d.norm() < 1e-12) throw std::invalid_argument("labelling: start and goal coincide");
  // In one dimension a hyperplane is a point: none contains both (randomNormal would never return).
  if (d.size() < 2)
    throw std::invalid_argument("labelling: a hyperplane through start and goal needs at least 2 dimensions, got " +
                                std::to_string(d.size()));
  std::mt19937_64 rng(seed);
  if (method == LabellingMethod::kRandom) {
    const Eigen::VectorXd w = randomNormal(d, rng);
    return apply(samples, regions, boundary_region, w, -w.dot(start), false);
  }
  double best_score = -1;
  Eigen::VectorXd best_w;
  for (int c = 0; c < candidates; ++c) {
    const Eigen::VectorXd w = randomNormal(d, rng);
    const RegionSides s = sides(samples, regions, w, -w.dot(start));
    int positive = 0, negative = 0;
    double consistency = 1;
    for (const auto& [region, sum] : s.sum) {
      if (region == boundary_region) continue;
      (sum >= 0 ? positive : negative) += 1;
      consistency = std::min(consistency, std::abs(sum) / s.count.at(region));
    }
    const bool split = (positive > 0 && negative > 0) || positive + negative < 2;
    // Both classes in the labelling that will be trained (boundary samples by their own side) first,
    // then obstacles on both sides, then the least ambiguous obstacle.
    const bool both = apply(samples, regions, boundary_region, w, -w.dot(start), true).both_classes;
    const double score = (both ? 4.0 : 0.0) + (split ? 2.0 : 0.0) + consistency;
    if (score > best_score) best_score = score, best_w = w;
  }
  return apply(samples, regions, boundary_region, best_w, -best_w.dot(start), true);
}

double measureRandomFailureRate(const Eigen::MatrixXd& samples, const std::vector<int>& regions,
                                int boundary_region, const Eigen::VectorXd& start,
                                const Eigen::VectorXd& goal, int trials, std::uint64_t seed) {
  int failures = 0;
  for (int t = 0; t < trials; ++t)
    failures += !labelByHyperplane(samples, regions, boundary_region, start, goal, LabellingMethod::kRandom,
                                   seed + t)
                     .both_classes;
  return static_cast<double>(failures) / trials;
}

}  // namespace svmp::planners
