#include "cspace/motion_validator.hpp"

#include <cmath>
#include <queue>
#include <stdexcept>

namespace svmp::cspace {

MotionValidator::MotionValidator(const CollisionChecker& checker, const ConfigurationSpace& space,
                                 double resolution)
    : checker_(checker), space_(space), resolution_(resolution) {
  if (!std::isfinite(resolution) || !(resolution > 0))
    throw std::invalid_argument("motion validator: resolution must be positive, got " +
                                std::to_string(resolution));
}

int MotionValidator::interiorPoints(double length) const {
  return std::max(0, static_cast<int>(std::ceil(length / resolution_)) - 1);
}

bool MotionValidator::isValid(const Eigen::Ref<const Eigen::VectorXd>& a,
                              const Eigen::Ref<const Eigen::VectorXd>& b) const {
  calls_.fetch_add(1, std::memory_order_relaxed);
  const int segments = interiorPoints(space_.distance(a, b)) + 1;
  if (segments < 2) return true;
  // Bisection order over the interior points 1..segments-1: midpoints of ever finer intervals.
  Eigen::VectorXd q(a.size());
  std::queue<std::pair<int, int>> intervals;
  intervals.emplace(0, segments);
  while (!intervals.empty()) {
    const auto [lo, hi] = intervals.front();
    intervals.pop();
    if (hi - lo < 2) continue;
    const int mid = (lo + hi) / 2;
    space_.interpolate(a, b, static_cast<double>(mid) / segments, q);
    if (!checker_.isValid(q)) return false;
    intervals.emplace(lo, mid);
    intervals.emplace(mid, hi);
  }
  return true;
}

bool MotionValidator::isValidIncludingEnd(const Eigen::Ref<const Eigen::VectorXd>& a,
                                          const Eigen::Ref<const Eigen::VectorXd>& b) const {
  if (!checker_.isValid(b)) {
    calls_.fetch_add(1, std::memory_order_relaxed);
    return false;
  }
  return isValid(a, b);
}

}  // namespace svmp::cspace
