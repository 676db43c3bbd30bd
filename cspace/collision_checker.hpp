#pragma once
// The exact validity checker: FCL primitives (cspace/validity_checker.hpp has the contract). The thesis'
// IsCollidingWith (ch. 4.3.2) returns the id of the obstacle the robot hits, 0 when free; joint limits
// and self-collision (IsMeetingConstraints) have ids of their own. Pairs are culled by the shapes'
// bounding boxes, kept here (through a grid beyond 8 obstacles, cspace/obstacle_grid.hpp); each pair
// left is decided by our GJK (cspace/convex_distance.hpp, intersects), FCL's narrow phase only where
// that run cannot decide. Where the two differ, the shapes overlap by under a micrometre and FCL's GJK
// tolerance misses it (docs/benchmarks.md). Every configuration tested is counted in collision_checks;
// every distance query (clearance, certified motion validation) in distance_queries.
//
// Thread safety: all const methods may be called concurrently. Each calling thread gets its own set of
// FCL collision objects and FK buffers (created on its first call and found again through a
// thread-local table keyed by a per-checker id that is never reused), so threads never share mutable
// FCL state; the counters are atomic.
#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <vector>

#include "cspace/validity_checker.hpp"

namespace svmp::cspace {

class ObstacleGrid;

class CollisionChecker final : public ValidityChecker {
 public:
  // Non-adjacent link pairs (robots::Robot::nonAdjacentLinkPairs) that touch in every one of 100
  // seeded random configurations (links joined at a spherical wrist, say) are excluded from
  // self-collision, as MoveIt's "always in collision".
  CollisionChecker(std::shared_ptr<const robots::Robot> robot, std::shared_ptr<const Environment> env,
                   bool self_collision = true);
  ~CollisionChecker();

  const robots::Robot& robot() const override { return *robot_; }
  const Environment& environment() const override { return *env_; }

  int check(const Eigen::Ref<const Eigen::VectorXd>& q) const override { return checkImpl(q, false); }
  int checkIncludingVirtual(const Eigen::Ref<const Eigen::VectorXd>& q) const override {
    return checkImpl(q, true);
  }
  bool hits(const Eigen::Ref<const Eigen::VectorXd>& q, int id) const override;
  // One placement of the robot and the grid's candidates; counts one collision check.
  std::vector<int> allHits(const Eigen::Ref<const Eigen::VectorXd>& q, bool include_virtual) const override;
  // The first kept self-collision pair (selfCollisionPairs) that collides at q, for messages; nullopt
  // when none does. Counts one collision check.
  std::optional<std::pair<int, int>> selfCollidingPair(const Eigen::Ref<const Eigen::VectorXd>& q) const;
  // The smallest distance between the robot and the real obstacles (0 in contact), to within 1e-6
  // of it from below (cspace/convex_distance.hpp; self-collision pairs not included); counts one
  // distance query.
  double clearance(const Eigen::Ref<const Eigen::VectorXd>& q) const override;
  // A lower bound on the smallest distance at q between the robot's links and the real obstacles,
  // and between the non-adjacent link pairs kept for self-collision: how far any point of the robot
  // may move before it can touch anything (0 when touching or penetrating, or outside joint limits;
  // +inf with nothing to hit). Each pair's value is a separating plane's
  // (cspace/convex_distance.hpp), never FCL's distance taken on trust. Counts one distance query.
  double freeDistance(const Eigen::Ref<const Eigen::VectorXd>& q) const;
  // The same per link, for the certified motion validator: d[k] bounds the distance from link k to
  // the real obstacles and, for each self pair, from the pair's distal link k to the other, capped at
  // cap[k] (pairs farther than the cap are not computed). Returns false, d all 0, when anything
  // touches or q is outside the joint limits. Counts one distance query.
  bool freeDistances(const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::VectorXd& cap,
                     Eigen::VectorXd& d) const;

  std::uint64_t collisionChecks() const override { return checks_.load(std::memory_order_relaxed); }
  std::uint64_t distanceQueries() const override { return distances_.load(std::memory_order_relaxed); }
  bool checksSelfCollision() const override { return !self_pairs_.empty(); }
  const std::vector<std::pair<int, int>>& selfCollisionPairs() const { return self_pairs_; }
  // Non-adjacent pairs left out because they touch in every sampled configuration (joined by
  // construction, or overlapping wherever the joint limits allow: then nothing checks them); not the
  // base and the first link with shapes, which meet at joint 1.
  const std::vector<std::pair<int, int>>& droppedSelfCollisionPairs() const { return dropped_pairs_; }

 private:
  struct Workspace;
  Workspace& workspace() const;
  int checkImpl(const Eigen::Ref<const Eigen::VectorXd>& q, bool include_virtual) const;
  void placeRobot(Workspace& ws, const Eigen::Ref<const Eigen::VectorXd>& q) const;
  bool linksCollide(Workspace& ws, int a, int b) const;
  // The first kept self-collision pair that collides with the robot placed in `ws`; null when none.
  const std::pair<int, int>* collidingSelfPair(Workspace& ws) const;
  std::unique_ptr<Workspace> makeWorkspace() const;

  std::shared_ptr<const robots::Robot> robot_;
  std::shared_ptr<const Environment> env_;
  std::unique_ptr<const ObstacleGrid> grid_;  // the broadphase, over many obstacles
  std::vector<std::pair<int, int>> self_pairs_, dropped_pairs_;
  std::uint64_t instance_id_;
  mutable std::mutex workspaces_mutex_;
  mutable std::vector<std::unique_ptr<Workspace>> workspaces_;
  mutable std::atomic<std::uint64_t> checks_{0};
  mutable std::atomic<std::uint64_t> distances_{0};
};

}  // namespace svmp::cspace
