#pragma once
// Configuration space: joint bounds, the weighted joint metric of thesis eq. 4.3
// dist(q0, q1) = sqrt(sum_d w_d (q0_d - q1_d)^2), straight-line interpolation and uniform sampling.
// Every random choice takes the caller's generator, so results follow from the seed.
// Thread safety: immutable after construction; const methods may run concurrently.
#include <Eigen/Core>
#include <random>

namespace svmp::cspace {

using Rng = std::mt19937_64;

class ConfigurationSpace {
 public:
  // Throws std::invalid_argument when sizes differ, a bound is not finite, lower >= upper or a weight
  // is not positive.
  ConfigurationSpace(Eigen::VectorXd lower, Eigen::VectorXd upper, Eigen::VectorXd weights);

  int dim() const { return static_cast<int>(lower_.size()); }
  const Eigen::VectorXd& lower() const { return lower_; }
  const Eigen::VectorXd& upper() const { return upper_; }
  const Eigen::VectorXd& weights() const { return weights_; }
  // sqrt(w_d): coordinates scaled by these make the weighted metric Euclidean (k-d trees use this).
  const Eigen::VectorXd& metricScale() const { return scale_; }

  double distance(const Eigen::Ref<const Eigen::VectorXd>& a,
                  const Eigen::Ref<const Eigen::VectorXd>& b) const {
    return (scale_.array() * (a - b).array()).matrix().norm();
  }
  // out = a + t (b - a)
  void interpolate(const Eigen::Ref<const Eigen::VectorXd>& a, const Eigen::Ref<const Eigen::VectorXd>& b,
                   double t, Eigen::Ref<Eigen::VectorXd> out) const {
    out = a + t * (b - a);
  }
  // The configuration one step of metric length `step` from `from` towards `to` (or `to` when closer).
  Eigen::VectorXd steer(const Eigen::Ref<const Eigen::VectorXd>& from,
                        const Eigen::Ref<const Eigen::VectorXd>& to, double step) const;
  bool contains(const Eigen::Ref<const Eigen::VectorXd>& q) const;
  void clamp(Eigen::Ref<Eigen::VectorXd> q) const { q = q.cwiseMax(lower_).cwiseMin(upper_); }
  void sampleUniform(Rng& rng, Eigen::Ref<Eigen::VectorXd> out) const;
  Eigen::VectorXd sampleUniform(Rng& rng) const;

 private:
  Eigen::VectorXd lower_, upper_, weights_, scale_;
};

}  // namespace svmp::cspace
