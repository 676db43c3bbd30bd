#pragma once
// The straight-line local planner shared by every planner: a segment is valid when every configuration
// on it at spacing <= resolution (in the weighted metric of eq. 4.3) is collision-free. Interior points
// are tested in bisection order (as OMPL's DiscreteMotionValidator) so blocked segments fail early.
// Each call counts one local_planner_call; each configuration tested counts one collision check in the
// checker.
#include <atomic>

#include "cspace/collision_checker.hpp"
#include "cspace/configuration_space.hpp"

namespace svmp::cspace {

class MotionValidator {
 public:
  // Throws std::invalid_argument when resolution is not positive and finite.
  MotionValidator(const CollisionChecker& checker, const ConfigurationSpace& space, double resolution);

  // Tests the interior of the segment a -> b; the end points are the caller's (roadmap nodes are
  // validated once, when they are created). Thread-safe.
  bool isValid(const Eigen::Ref<const Eigen::VectorXd>& a, const Eigen::Ref<const Eigen::VectorXd>& b) const;
  // Number of interior configurations isValid tests on a segment of that metric length.
  int interiorPoints(double length) const;
  // As isValid, but also the end point b (OMPL's checkMotion contract).
  bool isValidIncludingEnd(const Eigen::Ref<const Eigen::VectorXd>& a,
                           const Eigen::Ref<const Eigen::VectorXd>& b) const;

  double resolution() const { return resolution_; }
  const CollisionChecker& checker() const { return checker_; }
  const ConfigurationSpace& space() const { return space_; }
  std::uint64_t calls() const { return calls_.load(std::memory_order_relaxed); }
  void resetCounters() const { calls_.store(0, std::memory_order_relaxed); }

 private:
  const CollisionChecker& checker_;
  const ConfigurationSpace& space_;
  double resolution_;
  mutable std::atomic<std::uint64_t> calls_{0};
};

}  // namespace svmp::cspace
