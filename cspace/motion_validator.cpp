#include "cspace/motion_validator.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace svmp::cspace {

namespace {
thread_local const MotionStopScope* innermost_stop = nullptr;
}  // namespace

MotionStopScope::MotionStopScope(std::function<bool()> stop) : stop_(std::move(stop)), outer_(innermost_stop) {
  innermost_stop = this;
}

MotionStopScope::~MotionStopScope() { innermost_stop = outer_; }

bool MotionStopScope::stopped() { return innermost_stop && innermost_stop->stop_ && innermost_stop->stop_(); }

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

namespace {

// Checks the interior points of a segment cut into `segments` pieces in bisection order (midpoints of
// ever finer intervals, each level left to right), the order a queue of intervals gives, but in
// O(log n) memory: a queue holds up to n/2 intervals, 16 GB at the 2^30 checks a scenario allows.
class Bisection {
 public:
  Bisection(const ValidityChecker& checker, const ConfigurationSpace& space, const Eigen::Ref<const Eigen::VectorXd>& a,
            const Eigen::Ref<const Eigen::VectorXd>& b, std::int64_t segments)
      : checker_(checker), space_(space), a_(a), b_(b), segments_(segments), q_(a.size()) {}

  bool allValid() {
    for (int depth = 0;; ++depth) {
      deeper_ = false;
      if (!level(0, segments_, depth)) return false;
      if (!deeper_) return true;
    }
  }

 private:
  // The midpoints of the intervals `depth` halvings below [lo, hi).
  bool level(std::int64_t lo, std::int64_t hi, int depth) {
    if (hi - lo < 2) return true;
    const std::int64_t mid = lo + (hi - lo) / 2;
    if (depth > 0) return level(lo, mid, depth - 1) && level(mid, hi, depth - 1);
    deeper_ = deeper_ || hi - mid >= 2;  // [mid, hi) is the wider half
    if (++checked_ % kStopPollChecks == 0 && MotionStopScope::stopped()) return false;
    space_.interpolate(a_, b_, static_cast<double>(mid) / segments_, q_);
    return checker_.isValid(q_);
  }

  const ValidityChecker& checker_;
  const ConfigurationSpace& space_;
  const Eigen::Ref<const Eigen::VectorXd>& a_;
  const Eigen::Ref<const Eigen::VectorXd>& b_;
  const std::int64_t segments_;
  Eigen::VectorXd q_;
  bool deeper_ = false;
  std::int64_t checked_ = 0;
};

}  // namespace

bool DiscreteMotionValidator::isValid(const Eigen::Ref<const Eigen::VectorXd>& a,
                                      const Eigen::Ref<const Eigen::VectorXd>& b) const {
  countCall();
  const std::int64_t segments = interiorPoints(space_.distance(a, b)) + 1;
  if (segments < 2) return true;
  return Bisection(checker_, space_, a, b, segments).allValid();
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
    if ((i % kStopPollChecks == 0 && MotionStopScope::stopped()) || !checker_.isValid(q)) {
      last_valid = static_cast<double>(i - 1) / segments;
      return false;
    }
  }
  return true;
}

}  // namespace svmp::cspace
