#include "cspace/motion_validator.hpp"

#include <cmath>
#include <queue>
#include <stdexcept>
#include <string>

namespace svmp::cspace {

bool MotionValidator::isValidIncludingEnd(const Eigen::Ref<const Eigen::VectorXd>& a,
                                          const Eigen::Ref<const Eigen::VectorXd>& b) const {
  if (!checker().isValid(b)) {
    countCall();
    return false;
  }
  return isValid(a, b);
}

DiscreteMotionValidator::DiscreteMotionValidator(const ValidityChecker& checker, const ConfigurationSpace& space,
                                                 double resolution)
    : checker_(checker), space_(space), resolution_(resolution) {
  if (!std::isfinite(resolution) || !(resolution > 0))
    throw std::invalid_argument("motion validator: resolution must be positive, got " +
                                std::to_string(resolution));
}

std::int64_t DiscreteMotionValidator::interiorPoints(double length) const {
  const double segments = std::ceil(length / resolution_);
  // Compared in double before any conversion: NaN and huge values must not wrap to "few checks".
  if (!(segments <= static_cast<double>(kMaxSegmentChecks)))
    throw std::length_error("motion validator: a segment of metric length " + std::to_string(length) +
                            " at resolution " + std::to_string(resolution_) + " needs more than " +
                            std::to_string(kMaxSegmentChecks) + " checks");
  return std::max<std::int64_t>(0, static_cast<std::int64_t>(segments) - 1);
}

bool DiscreteMotionValidator::isValid(const Eigen::Ref<const Eigen::VectorXd>& a,
                                      const Eigen::Ref<const Eigen::VectorXd>& b) const {
  countCall();
  const std::int64_t segments = interiorPoints(space_.distance(a, b)) + 1;
  if (segments < 2) return true;
  // Bisection order over the interior points 1..segments-1: midpoints of ever finer intervals.
  Eigen::VectorXd q(a.size());
  std::queue<std::pair<std::int64_t, std::int64_t>> intervals;
  intervals.emplace(0, segments);
  while (!intervals.empty()) {
    const auto [lo, hi] = intervals.front();
    intervals.pop();
    if (hi - lo < 2) continue;
    const std::int64_t mid = lo + (hi - lo) / 2;
    space_.interpolate(a, b, static_cast<double>(mid) / segments, q);
    if (!checker_.isValid(q)) return false;
    intervals.emplace(lo, mid);
    intervals.emplace(mid, hi);
  }
  return true;
}

bool DiscreteMotionValidator::checkMotion(const Eigen::Ref<const Eigen::VectorXd>& a,
                                          const Eigen::Ref<const Eigen::VectorXd>& b,
                                          double& last_valid) const {
  // In order from a, so that the last valid configuration is known (RRT-style extension).
  countCall();
  const std::int64_t segments = interiorPoints(space_.distance(a, b)) + 1;
  Eigen::VectorXd q(a.size());
  for (std::int64_t i = 1; i <= segments; ++i) {
    space_.interpolate(a, b, static_cast<double>(i) / segments, q);
    if (!checker_.isValid(q)) {
      last_valid = static_cast<double>(i - 1) / segments;
      return false;
    }
  }
  return true;
}

}  // namespace svmp::cspace
