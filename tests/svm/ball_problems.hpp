// Synthetic SVM problems shaped like SVMP's: samples inside unions of overlapping balls (one union
// per obstacle class) in the unit cube, labelled by class. Seeded, shared by tests and benchmarks.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <random>
#include <vector>

namespace svmp::svm::testing {

struct BallProblem {
  Eigen::MatrixXd X;        // d x n
  std::vector<int> labels;  // class 1..classes
  double ball_radius = 0;
  Eigen::VectorXd binary(int positive_class = 1) const {
    Eigen::VectorXd y(X.cols());
    for (Eigen::Index i = 0; i < X.cols(); ++i) y[i] = labels[i] == positive_class ? 1.0 : -1.0;
    return y;
  }
};

// Each class is a chain of `balls` balls of radius r whose centres random-walk by r (so they
// overlap); different classes may overlap too, which makes some samples ambiguous (bounded SVs).
// Default radius: 0.08 in the plane (separate obstacles, as in the thesis' 2-D examples), 0.2 in
// higher dimensions (chains of different classes touch and overlap).
inline BallProblem makeBallProblem(int d, int n, int classes, unsigned long long seed,
                                   int balls = 4, double r = -1) {
  if (r <= 0) r = d <= 2 ? 0.08 : 0.2;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<Eigen::VectorXd> centres;
  for (int c = 0; c < classes; ++c) {
    Eigen::VectorXd x(d);
    for (int k = 0; k < d; ++k) x[k] = r + (1 - 2 * r) * uni(rng);
    for (int b = 0; b < balls; ++b) {
      centres.push_back(x);
      Eigen::VectorXd step(d);
      for (int k = 0; k < d; ++k) step[k] = normal(rng);
      x += r * step.normalized();
      for (int k = 0; k < d; ++k) x[k] = std::min(1 - r, std::max(r, x[k]));
    }
  }
  BallProblem p;
  p.ball_radius = r;
  p.X.resize(d, n);
  p.labels.resize(n);
  for (int i = 0; i < n; ++i) {
    // first sample of class 1 so that libsvm's first label is +1
    const int c = i == 0 ? 0 : static_cast<int>(uni(rng) * classes) % classes;
    const int b = static_cast<int>(uni(rng) * balls) % balls;
    Eigen::VectorXd dir(d);
    for (int k = 0; k < d; ++k) dir[k] = normal(rng);
    const double rad = r * std::pow(uni(rng), 1.0 / d);
    p.X.col(i) = centres[c * balls + b] + rad * dir.normalized();
    p.labels[i] = c + 1;
  }
  return p;
}

// Queries near the decision boundary: training points plus Gaussian noise of std `noise`.
inline Eigen::MatrixXd nearQueries(const Eigen::MatrixXd& X, int count, double noise,
                                   unsigned long long seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, noise);
  std::uniform_int_distribution<Eigen::Index> pick(0, X.cols() - 1);
  Eigen::MatrixXd Q(X.rows(), count);
  for (int i = 0; i < count; ++i) {
    Q.col(i) = X.col(pick(rng));
    for (Eigen::Index k = 0; k < X.rows(); ++k) Q(k, i) += normal(rng);
  }
  return Q;
}

}  // namespace svmp::svm::testing
