#pragma once
// OMPL's seams as ours: a SpaceInformation's StateValidityChecker as a cspace::ValidityChecker and its
// MotionValidator as a cspace::MotionValidator (OMPL 1.5 API: ompl::base::SpaceInformation::isValid,
// MotionValidator::checkMotion), so our planners run on a user's checker. Such a checker says valid or
// not and nothing else: it is reported as one obstacle class (id 1, named after the checker), it has no
// robot model (robot() throws std::logic_error), no self-collision region, and the clearance OMPL's
// checker gives (0 unless it computes one). Planners that need more (SVMP's obstacle trees, the local
// planner's IK samples, SVPP's obstacle polygons) refuse it: planners/ompl/svm_planners.hpp.
// A foreign space's configurations are its states' coordinates (unit metric weights); the motion
// validator may also wrap a foreign MotionValidator on our scaled space (it scales by the space's
// metricScale).
//
// Thread safety: a user's checker need not be thread-safe, so the planners give these one thread.
// Each check allocates its own OMPL state; counters are atomic.
#include <atomic>

#include <ompl/base/SpaceInformation.h>

#include "cspace/environment.hpp"
#include "cspace/motion_validator.hpp"
#include "cspace/validity_checker.hpp"

namespace svmp::ompl_planners {

namespace ob = ::ompl::base;

// The bounds of a RealVectorStateSpace with unit weights; throws std::invalid_argument for other
// state spaces.
cspace::ConfigurationSpace configurationSpaceOf(const ob::SpaceInformation& si);

class ForeignValidityChecker final : public cspace::ValidityChecker {
 public:
  explicit ForeignValidityChecker(ob::SpaceInformationPtr si);
  const robots::Robot& robot() const override;  // throws std::logic_error: there is none
  const cspace::Environment& environment() const override { return environment_; }
  // kFree, or 1 (the single obstacle class) when the SpaceInformation says invalid.
  int check(const Eigen::Ref<const Eigen::VectorXd>& q) const override;
  int checkIncludingVirtual(const Eigen::Ref<const Eigen::VectorXd>& q) const override { return check(q); }
  bool hits(const Eigen::Ref<const Eigen::VectorXd>& q, int id) const override;
  double clearance(const Eigen::Ref<const Eigen::VectorXd>& q) const override;
  bool checksSelfCollision() const override { return false; }
  std::uint64_t collisionChecks() const override { return checks_.load(std::memory_order_relaxed); }

 private:
  ob::SpaceInformationPtr si_;
  cspace::Environment environment_;
  Eigen::VectorXd scale_;  // ones: a foreign space's states are configurations
  mutable std::atomic<std::uint64_t> checks_{0};
};

class ForeignMotionValidator final : public cspace::MotionValidator {
 public:
  // `checker` is the one our planners count with (usually a ForeignValidityChecker of the same si).
  ForeignMotionValidator(ob::SpaceInformationPtr si, const cspace::ValidityChecker& checker,
                         const cspace::ConfigurationSpace& space);
  // OMPL's checkMotion tests the end b as well: stricter than the interior our contract asks for.
  bool isValid(const Eigen::Ref<const Eigen::VectorXd>& a, const Eigen::Ref<const Eigen::VectorXd>& b) const override;
  bool checkMotion(const Eigen::Ref<const Eigen::VectorXd>& a, const Eigen::Ref<const Eigen::VectorXd>& b,
                   double& last_valid) const override;
  const cspace::ValidityChecker& checker() const override { return checker_; }
  const cspace::ConfigurationSpace& space() const override { return space_; }
  // OMPL's: the checking resolution (a fraction of the maximum extent) times the maximum extent.
  double resolution() const override;

 private:
  ob::SpaceInformationPtr si_;
  const cspace::ValidityChecker& checker_;
  const cspace::ConfigurationSpace& space_;
};

}  // namespace svmp::ompl_planners
