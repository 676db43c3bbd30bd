#pragma once
// The seam every planner checks configurations through (docs/architecture.md, "Seams"): the exact FCL
// checker implements it today (cspace/collision_checker.hpp); a learned proxy (Fastron) or a test
// double may implement it too. Ids follow the thesis' IsCollidingWith (ch. 4.3.2): 0 free, the id of the
// obstacle hit, or one of the negative ids below.
//
// Thread safety: implementations make every const method safe to call from many threads at once.
#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "cspace/environment.hpp"
#include "robots/robot.hpp"

namespace svmp::cspace {

inline constexpr int kFree = 0;
inline constexpr int kJointLimitHit = -1;
inline constexpr int kSelfCollisionHit = -2;
inline constexpr int kPredictedHit = -3;  // a learned proxy predicts a collision (cspace/fastron_checker.hpp)

// What a check() result means, for messages: "free", "outside the joint limits", "in self-collision"
// or "in collision with obstacle 'NAME'".
inline std::string describeHit(const Environment& env, int hit) {
  if (hit == kFree) return "free";
  if (hit == kJointLimitHit) return "outside the joint limits";
  if (hit == kSelfCollisionHit) return "in self-collision";
  if (hit == kPredictedHit) return "predicted in collision by the proxy checker";
  return "in collision with obstacle '" + env.byId(hit).name + "'";
}

class ValidityChecker {
 public:
  virtual ~ValidityChecker() = default;

  virtual const robots::Robot& robot() const = 0;
  virtual const Environment& environment() const = 0;

  // kJointLimitHit, else the lowest id of a real obstacle the robot overlaps, else kSelfCollisionHit,
  // else kFree. Virtual obstacles are ignored: they may be touched. Counts one collision check.
  virtual int check(const Eigen::Ref<const Eigen::VectorXd>& q) const = 0;
  bool isValid(const Eigen::Ref<const Eigen::VectorXd>& q) const { return check(q) == kFree; }
  // As check(), but virtual obstacles count too (obstacle sampling of guide obstacles, ch. 2.3).
  virtual int checkIncludingVirtual(const Eigen::Ref<const Eigen::VectorXd>& q) const = 0;
  // True when the robot (within joint limits) overlaps obstacle `id` (real or virtual), or, for
  // id == kSelfCollisionHit, when two of its non-adjacent links overlap. Counts one collision check.
  virtual bool hits(const Eigen::Ref<const Eigen::VectorXd>& q, int id) const = 0;
  // The ids of every obstacle the robot overlaps at q, ascending (virtual ones too when
  // include_virtual), then kSelfCollisionHit when two of its non-adjacent links overlap; empty
  // outside the joint limits. What hits() answers obstacle by obstacle, in one query (the obstacle
  // sampler's last root search asks it of every draw). This default asks hits() of each obstacle.
  virtual std::vector<int> allHits(const Eigen::Ref<const Eigen::VectorXd>& q, bool include_virtual) const {
    std::vector<int> ids;
    for (const Obstacle& o : environment().obstacles())
      if ((include_virtual || !o.is_virtual) && hits(q, o.id)) ids.push_back(o.id);
    if (checksSelfCollision() && hits(q, kSelfCollisionHit)) ids.push_back(kSelfCollisionHit);
    return ids;
  }
  // Minimum distance between the robot and the real obstacles; 0 when touching or penetrating. Not
  // counted as a collision check.
  virtual double clearance(const Eigen::Ref<const Eigen::VectorXd>& q) const = 0;
  // True when check() tests pairs of the robot's own links (the self-collision region is then one more
  // C-obstacle to sample, thesis ch. 4.3.2).
  virtual bool checksSelfCollision() const = 0;

  // Configurations tested since construction (atomic; read differences, see CounterScope in planners/planner.cpp).
  virtual std::uint64_t collisionChecks() const = 0;
  // Distance queries since construction (clearance, certified motion validation); 0 for checkers that
  // answer none.
  virtual std::uint64_t distanceQueries() const { return 0; }
};

}  // namespace svmp::cspace
