#include "cspace/certified_motion_validator.hpp"

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace svmp::cspace {

CertifiedMotionValidator::CertifiedMotionValidator(const CollisionChecker& exact, const ConfigurationSpace& space,
                                                   double resolution)
    : exact_(exact), space_(space), resolution_(resolution), tolerance_(1e-6 * resolution) {
  if (!std::isfinite(resolution) || !(resolution > 0))
    throw std::invalid_argument("certified motion validator: resolution must be positive, got " +
                                std::to_string(resolution));
}

bool CertifiedMotionValidator::prove(const Eigen::Ref<const Eigen::VectorXd>& a,
                                     const Eigen::Ref<const Eigen::VectorXd>& b, bool need_prefix,
                                     double& proven) const {
  proven = 0;
  std::int64_t queries = 0;
  Eigen::VectorXd q(a.size());
  auto distanceAt = [&](double t) {
    ++queries;
    space_.interpolate(a, b, t, q);
    return exact_.freeDistance(q);
  };
  const double length = exact_.robot().displacementBound(a, b);
  const double d0 = distanceAt(0);
  bool ok = d0 > tolerance_;
  if (ok && !(length > 0)) {  // no motion: the start is the whole segment
    proven = 1;
  } else if (ok) {
    // Intervals still to prove, the leftmost on top, so the proven prefix grows from a.
    struct Interval {
      double t0, d0, t1, d1;
    };
    std::vector<Interval> stack = {{0, d0, 1, distanceAt(1)}};
    ok = stack.back().d1 > tolerance_;
    if (!ok && !need_prefix) stack.clear();  // an end in contact fails at once
    while (!stack.empty()) {
      const Interval i = stack.back();
      // A right end closer than the tolerance (or outside the joint limits, which no ball covers)
      // is never part of a proof: such an interval is only bisected, to push the proven prefix
      // towards it.
      const bool blocked = i.d1 <= tolerance_;
      if (!blocked && i.d0 + i.d1 > (i.t1 - i.t0) * length) {
        stack.pop_back();
        proven = i.t1;
        continue;
      }
      const double mid = 0.5 * (i.t0 + i.t1);
      if (queries >= kMaxDistanceQueries || !(mid > i.t0 && mid < i.t1) ||
          (blocked && (i.t1 - i.t0) * length <= tolerance_)) {
        ok = false;
        break;
      }
      const double dm = distanceAt(mid);
      if (dm <= tolerance_) {
        ok = false;
        // Nothing beyond mid can be proven; with need_prefix, push the proven prefix towards it.
        if (!need_prefix || (mid - i.t0) * length <= tolerance_) break;
        stack = {{i.t0, i.d0, mid, dm}};
        continue;
      }
      stack.back() = {mid, dm, i.t1, i.d1};
      stack.push_back({i.t0, i.d0, mid, dm});
    }
  }
  distances_.fetch_add(static_cast<std::uint64_t>(queries), std::memory_order_relaxed);
  return ok;
}

bool CertifiedMotionValidator::isValid(const Eigen::Ref<const Eigen::VectorXd>& a,
                                       const Eigen::Ref<const Eigen::VectorXd>& b) const {
  countCall();
  double proven = 0;
  return prove(a, b, false, proven);
}

bool CertifiedMotionValidator::checkMotion(const Eigen::Ref<const Eigen::VectorXd>& a,
                                           const Eigen::Ref<const Eigen::VectorXd>& b, double& last_valid) const {
  countCall();
  double proven = 0;
  if (prove(a, b, true, proven)) return true;
  last_valid = proven < 1 ? proven : std::nextafter(1.0, 0.0);
  return false;
}

}  // namespace svmp::cspace
