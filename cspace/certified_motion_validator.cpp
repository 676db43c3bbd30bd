#include "cspace/certified_motion_validator.hpp"

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace svmp::cspace {

CertifiedMotionValidator::CertifiedMotionValidator(const CollisionChecker& exact, const ConfigurationSpace& space,
                                                   double resolution)
    : exact_(exact), space_(space), resolution_(resolution), tolerance_(toleranceFor(resolution)) {
  if (!std::isfinite(resolution) || !(resolution > 0))
    throw std::invalid_argument("certified motion validator: resolution must be positive, got " +
                                std::to_string(resolution));
}

bool CertifiedMotionValidator::prove(const Eigen::Ref<const Eigen::VectorXd>& a,
                                     const Eigen::Ref<const Eigen::VectorXd>& b, bool need_prefix,
                                     double& proven) const {
  proven = 0;
  Eigen::VectorXd bound;  // per link, over the whole segment
  exact_.robot().linkDisplacementBounds(a, b, bound);
  const double length = bound.maxCoeff();
  // A point is used only in intervals of at most `span`: a distance beyond the link's displacement
  // over the span proves no more, so it is capped there (2 tolerances keep a link that does not
  // move provable), and pairs beyond the cap are skipped by their bounding boxes.
  Eigen::VectorXd cap;
  // Per query r: the per-link distances at links * r, and their minimum.
  const int links = static_cast<int>(bound.size());
  std::vector<double> distances, closest;
  Eigen::VectorXd q(a.size()), d;
  auto distanceAt = [&](double t, double span) {
    cap = span * bound.array() + 2 * tolerance_;
    space_.interpolate(a, b, t, q);
    exact_.freeDistances(q, cap, d);
    distances.insert(distances.end(), d.data(), d.data() + links);
    closest.push_back(d.minCoeff());
    return static_cast<int>(closest.size()) - 1;
  };
  auto queries = [&] { return static_cast<std::int64_t>(closest.size()); };
  // [t0, t1] is free when for every link the free balls at both ends cover its motion.
  auto covered = [&](int r0, int r1, double span) {
    for (int k = 0; k < links; ++k)
      if (!(distances[links * r0 + k] + distances[links * r1 + k] > span * bound[k])) return false;
    return true;
  };
  const int r0 = distanceAt(0, 1);
  bool ok = closest[r0] > tolerance_;
  if (ok && !(length > 0)) {  // no motion: the start is the whole segment
    proven = 1;
  } else if (ok) {
    // Intervals still to prove, the leftmost on top, so the proven prefix grows from a.
    struct Interval {
      double t0;
      int r0;
      double t1;
      int r1;
    };
    std::vector<Interval> stack = {{0, r0, 1, distanceAt(1, 1)}};
    ok = closest[stack.back().r1] > tolerance_;
    if (!ok && !need_prefix) stack.clear();  // an end in contact fails at once
    while (!stack.empty()) {
      const Interval i = stack.back();
      // A right end closer than the tolerance (or outside the joint limits, which no ball covers)
      // is never part of a proof: such an interval is only bisected, to push the proven prefix
      // towards it.
      const bool blocked = closest[i.r1] <= tolerance_;
      if (!blocked && covered(i.r0, i.r1, i.t1 - i.t0)) {
        stack.pop_back();
        proven = i.t1;
        continue;
      }
      const double mid = 0.5 * (i.t0 + i.t1);
      if (queries() >= kMaxDistanceQueries || !(mid > i.t0 && mid < i.t1) ||
          (blocked && (i.t1 - i.t0) * length <= tolerance_)) {
        ok = false;
        break;
      }
      const int rm = distanceAt(mid, 0.5 * (i.t1 - i.t0));
      if (closest[rm] <= tolerance_) {
        ok = false;
        // Nothing beyond mid can be proven; with need_prefix, push the proven prefix towards it.
        if (!need_prefix || (mid - i.t0) * length <= tolerance_) break;
        stack = {{i.t0, i.r0, mid, rm}};
        continue;
      }
      stack.back() = {mid, rm, i.t1, i.r1};
      stack.push_back({i.t0, i.r0, mid, rm});
    }
  }
  distances_.fetch_add(static_cast<std::uint64_t>(queries()), std::memory_order_relaxed);
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
