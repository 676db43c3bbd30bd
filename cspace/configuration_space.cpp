#include "cspace/configuration_space.hpp"

#include <sstream>
#include <stdexcept>

namespace svmp::cspace {

ConfigurationSpace::ConfigurationSpace(Eigen::VectorXd lower, Eigen::VectorXd upper,
                                       Eigen::VectorXd weights)
    : lower_(std::move(lower)), upper_(std::move(upper)), weights_(std::move(weights)) {
  if (lower_.size() == 0 || lower_.size() != upper_.size() || weights_.size() != lower_.size()) {
    std::ostringstream err;
    err << "configuration space: bounds and weights must have equal non-zero sizes, got "
        << lower_.size() << ", " << upper_.size() << ", " << weights_.size();
    throw std::invalid_argument(err.str());
  }
  for (int i = 0; i < dim(); ++i) {
    if (!std::isfinite(lower_[i]) || !std::isfinite(upper_[i]) || !(lower_[i] < upper_[i])) {
      std::ostringstream err;
      err << "configuration space: dimension " << i + 1 << " bounds must be finite with lower < upper, got ["
          << lower_[i] << ", " << upper_[i] << "]";
      throw std::invalid_argument(err.str());
    }
    if (!std::isfinite(weights_[i]) || !(weights_[i] > 0)) {
      std::ostringstream err;
      err << "configuration space: metric weight " << i + 1 << " must be positive, got " << weights_[i];
      throw std::invalid_argument(err.str());
    }
  }
  scale_ = weights_.cwiseSqrt();
}

Eigen::VectorXd ConfigurationSpace::steer(const Eigen::Ref<const Eigen::VectorXd>& from,
                                          const Eigen::Ref<const Eigen::VectorXd>& to,
                                          double step) const {
  const double d = distance(from, to);
  if (d <= step) return to;
  return from + (step / d) * (to - from);
}

bool ConfigurationSpace::contains(const Eigen::Ref<const Eigen::VectorXd>& q) const {
  return q.size() == dim() && ((q - lower_).array() >= 0).all() && ((upper_ - q).array() >= 0).all();
}

void ConfigurationSpace::sampleUniform(Rng& rng, Eigen::Ref<Eigen::VectorXd> out) const {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int i = 0; i < dim(); ++i) out[i] = lower_[i] + unit(rng) * (upper_[i] - lower_[i]);
}

Eigen::VectorXd ConfigurationSpace::sampleUniform(Rng& rng) const {
  Eigen::VectorXd q(dim());
  sampleUniform(rng, q);
  return q;
}

}  // namespace svmp::cspace
