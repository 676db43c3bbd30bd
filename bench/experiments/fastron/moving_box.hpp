#pragma once
// The workspace of the Fastron experiments (Das & Yip 2019, sec. IV): the scenario's robot with one box
// obstacle of random size that moves in random directions. The box's centre stays in a ring around the
// robot's base (radius [ring_inner, ring_outer] from the z axis, height [z_low, z_high]) so it can
// neither swallow the base (every configuration in collision) nor leave the arm's reach.
// Thread safety: a value type; use one per thread.
#include <Eigen/Geometry>
#include <memory>
#include <random>

#include "cspace/collision_checker.hpp"
#include "cspace/scenario/scenario.hpp"

namespace svmp::experiments::fastron {

struct MovingBoxOptions {
  double min_side = 0.1, max_side = 0.4;  // m, each side uniform in [min, max]
  double ring_inner = 0.35, ring_outer = 0.75, z_low = 0.0, z_high = 0.8;
  double move = 0.05;                     // m per move, random direction
};

class MovingBox {
 public:
  MovingBox(const MovingBoxOptions& options, std::mt19937_64& rng);
  // A box of given sides and pose (the planning experiment's obstacle; it keeps its orientation).
  MovingBox(const MovingBoxOptions& options, const Eigen::Vector3d& sides, const Eigen::Isometry3d& pose);
  // Whether a centre lies in the region the box moves in.
  static bool inRegion(const MovingBoxOptions& options, const Eigen::Vector3d& centre);
  // One move of options.move in a random direction, reflected back into the allowed region.
  void move(std::mt19937_64& rng);
  const Eigen::Vector3d& centre() const { return centre_; }
  const Eigen::Vector3d& sides() const { return sides_; }
  // This box, then `fixed` (obstacles that do not move).
  std::shared_ptr<const cspace::Environment> environment(const std::vector<cspace::Obstacle>& fixed = {}) const;
  // The exact checker of the scenario's robot with this box and `fixed` (self-collision as the scenario
  // says).
  std::unique_ptr<cspace::CollisionChecker> checker(const cspace::Scenario& scenario,
                                                    const std::vector<cspace::Obstacle>& fixed = {}) const;

 private:
  void keepInside();
  MovingBoxOptions options_;
  Eigen::Vector3d sides_, centre_;
  Eigen::Matrix3d rotation_ = Eigen::Matrix3d::Identity();
};

}  // namespace svmp::experiments::fastron
