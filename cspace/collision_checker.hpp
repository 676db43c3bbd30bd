#pragma once
// Collision checking through FCL primitives: the thesis' IsCollidingWith (ch. 4.3.2) returns the id of
// the obstacle the robot hits, 0 when free; joint limits and self-collision (IsMeetingConstraints) have
// ids of their own. Every configuration tested is counted in collision_checks.
//
// Thread safety: all const methods may be called concurrently. Each calling thread gets its own set of
// FCL collision objects and FK buffers (created on its first call), so threads never share mutable FCL
// state; the counters are atomic.
#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <vector>

#include "cspace/environment.hpp"
#include "robots/robot.hpp"

namespace svmp::cspace {

inline constexpr int kFree = 0;
inline constexpr int kJointLimitHit = -1;
inline constexpr int kSelfCollisionHit = -2;

class CollisionChecker {
 public:
  // Non-adjacent link pairs that touch in every one of 100 seeded random configurations (links joined
  // at a spherical wrist, say) are excluded from self-collision, as MoveIt's "always in collision".
  CollisionChecker(std::shared_ptr<const robots::Robot> robot, std::shared_ptr<const Environment> env,
                   bool self_collision = true);
  ~CollisionChecker();

  const robots::Robot& robot() const { return *robot_; }
  const Environment& environment() const { return *env_; }

  // kJointLimitHit, else the lowest id of a real obstacle the robot overlaps, else kSelfCollisionHit,
  // else kFree. Virtual obstacles are ignored: they may be touched.
  int check(const Eigen::Ref<const Eigen::VectorXd>& q) const { return checkImpl(q, false); }
  bool isValid(const Eigen::Ref<const Eigen::VectorXd>& q) const { return check(q) == kFree; }
  // As check(), but virtual obstacles count too (obstacle sampling of guide obstacles, ch. 2.3).
  int checkIncludingVirtual(const Eigen::Ref<const Eigen::VectorXd>& q) const {
    return checkImpl(q, true);
  }
  // True when the robot (within joint limits) overlaps obstacle `id` (real or virtual), or, for
  // id == kSelfCollisionHit, when two of its non-adjacent links overlap.
  bool hits(const Eigen::Ref<const Eigen::VectorXd>& q, int id) const;
  // Minimum FCL distance between the robot and the real obstacles; 0 when touching or penetrating.
  // Not counted as a collision check.
  double clearance(const Eigen::Ref<const Eigen::VectorXd>& q) const;

  std::uint64_t collisionChecks() const { return checks_.load(std::memory_order_relaxed); }
  void resetCounters() const { checks_.store(0, std::memory_order_relaxed); }
  const std::vector<std::pair<int, int>>& selfCollisionPairs() const { return self_pairs_; }

 private:
  struct Workspace;
  Workspace& workspace() const;
  int checkImpl(const Eigen::Ref<const Eigen::VectorXd>& q, bool include_virtual) const;
  void placeRobot(Workspace& ws, const Eigen::Ref<const Eigen::VectorXd>& q) const;
  bool linksCollide(Workspace& ws, int a, int b) const;
  std::unique_ptr<Workspace> makeWorkspace() const;

  std::shared_ptr<const robots::Robot> robot_;
  std::shared_ptr<const Environment> env_;
  std::vector<std::pair<int, int>> self_pairs_;
  std::uint64_t instance_id_;
  mutable std::mutex workspaces_mutex_;
  mutable std::vector<std::unique_ptr<Workspace>> workspaces_;
  mutable std::atomic<std::uint64_t> checks_{0};
};

}  // namespace svmp::cspace
