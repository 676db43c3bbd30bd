#pragma once
// The straight-line local planner every planner connects configurations with, as a seam
// (docs/architecture.md, "Seams"): MotionValidator is the interface; DiscreteMotionValidator samples the
// segment at the scenario's resolution (the thesis' protocol, so CD and LP stay comparable);
// CertifiedMotionValidator (cspace/certified_motion_validator.hpp) proves it free.
// Each call of isValid / isValidIncludingEnd / checkMotion counts one local_planner_call.
//
// Thread safety: every const method may be called from many threads at once (the counter is atomic).
#include <atomic>
#include <cstdint>
#include <functional>

#include "cspace/configuration_space.hpp"
#include "cspace/validity_checker.hpp"

namespace svmp::cspace {

// The most configurations one segment may need; a longer one is refused (std::length_error naming the
// resolution and the segment's length), never reported free.
inline constexpr std::int64_t kMaxSegmentChecks = std::int64_t{1} << 30;

// The calling thread's stop for long segments, in force while the scope lives (planners::Planner opens
// one around each solve, build and query with its time limit): a segment polls it every
// kStopPollChecks configurations and, when it fires, is reported blocked. Blocked is the safe answer
// (no path is made of it), and the planner, polling the same stop, then ends with its time limit. A
// segment of 2^30 checks took 55 s whatever the limit. Threads that did not open a scope never stop
// a segment (an OpenMP team's other threads check short steps).
class MotionStopScope {
 public:
  explicit MotionStopScope(std::function<bool()> stop);
  ~MotionStopScope();
  MotionStopScope(const MotionStopScope&) = delete;
  MotionStopScope& operator=(const MotionStopScope&) = delete;
  // Whether the innermost scope of this thread has fired (false without one).
  static bool stopped();

 private:
  std::function<bool()> stop_;
  const MotionStopScope* outer_;
};
inline constexpr std::int64_t kStopPollChecks = 4096;

class MotionValidator {
 public:
  virtual ~MotionValidator() = default;

  // Tests the interior of the segment a -> b; the end points are the caller's (roadmap nodes are
  // validated once, when they are created).
  virtual bool isValid(const Eigen::Ref<const Eigen::VectorXd>& a,
                       const Eigen::Ref<const Eigen::VectorXd>& b) const = 0;
  // As isValid, but also the end point b (OMPL's checkMotion contract: a is valid).
  bool isValidIncludingEnd(const Eigen::Ref<const Eigen::VectorXd>& a,
                           const Eigen::Ref<const Eigen::VectorXd>& b) const;
  // Walks from a (valid) towards b, end included. On failure, last_valid is a fraction t in [0, 1) such
  // that a + t (b - a) is valid and the segment up to it was tested (OMPL's last-valid-state contract).
  virtual bool checkMotion(const Eigen::Ref<const Eigen::VectorXd>& a,
                           const Eigen::Ref<const Eigen::VectorXd>& b, double& last_valid) const = 0;

  virtual const ValidityChecker& checker() const = 0;
  virtual const ConfigurationSpace& space() const = 0;
  // The sampling resolution in the weighted metric of eq. 4.3.
  virtual double resolution() const = 0;
  std::uint64_t calls() const { return calls_.load(std::memory_order_relaxed); }
  // Distance queries made for this validator (certified validation); 0 for sampled validation.
  virtual std::uint64_t distanceQueries() const { return 0; }

 protected:
  void countCall() const { calls_.fetch_add(1, std::memory_order_relaxed); }

 private:
  mutable std::atomic<std::uint64_t> calls_{0};
};

// A segment is valid when every configuration on it at spacing <= resolution (weighted metric) is.
// Interior points are tested in bisection order (as OMPL's DiscreteMotionValidator) so blocked segments
// fail early. Each configuration tested counts one collision check in the checker.
class DiscreteMotionValidator final : public MotionValidator {
 public:
  // Throws std::invalid_argument when resolution is not positive and finite.
  DiscreteMotionValidator(const ValidityChecker& checker, const ConfigurationSpace& space, double resolution);

  bool isValid(const Eigen::Ref<const Eigen::VectorXd>& a,
               const Eigen::Ref<const Eigen::VectorXd>& b) const override;
  bool checkMotion(const Eigen::Ref<const Eigen::VectorXd>& a, const Eigen::Ref<const Eigen::VectorXd>& b,
                   double& last_valid) const override;
  // Interior configurations isValid tests on a segment of that metric length; throws std::length_error
  // above kMaxSegmentChecks.
  std::int64_t interiorPoints(double length) const;

  const ValidityChecker& checker() const override { return checker_; }
  const ConfigurationSpace& space() const override { return space_; }
  double resolution() const override { return resolution_; }

 private:
  const ValidityChecker& checker_;
  const ConfigurationSpace& space_;
  double resolution_;
};

}  // namespace svmp::cspace
