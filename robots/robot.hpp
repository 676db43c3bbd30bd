#pragma once
// The kinematic model every planner works on: dof, joint limits, forward kinematics giving every link's
// pose, link shapes (FCL primitives) and the control points of the FK kernel (Das & Yip 2019, sec. III:
// each distinct moving joint origin plus the tool tip).
//
// Thread safety: a Robot is immutable after construction; every const method may be called from many
// threads at once (callers own the output buffers).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "robots/shape.hpp"

namespace svmp::robots {

using Poses = std::vector<Eigen::Isometry3d>;

class Robot {
 public:
  virtual ~Robot() = default;

  const std::string& name() const { return name_; }
  int dof() const { return static_cast<int>(lower_.size()); }
  int numLinks() const { return static_cast<int>(link_shapes_.size()); }
  // 2 for robots that move in the plane z = 0 (point 2D, planar arms), 3 otherwise.
  int workspaceDim() const { return workspace_dim_; }
  const Eigen::VectorXd& lowerLimits() const { return lower_; }
  const Eigen::VectorXd& upperLimits() const { return upper_; }
  bool withinLimits(const Eigen::Ref<const Eigen::VectorXd>& q) const;
  const std::vector<Shape>& linkShapes(int link) const { return link_shapes_[link]; }
  // The part of the robot no joint moves (a DH arm's column from its base to joint 1), in the world
  // frame. It counts for self-collision only, as link kBase: an obstacle inside it would make every
  // configuration collide, so there is nothing for a planner to learn from it.
  static constexpr int kBase = -1;
  const std::vector<Shape>& baseShapes() const { return base_shapes_; }
  // "base" for kBase, else the link's index.
  static std::string linkLabel(int link);
  // Links that may collide with each other: not adjacent along the chain (links without shapes are
  // skipped when deciding adjacency, so a spherical wrist's zero-length links do not hide a neighbour).
  // And (kBase, k) for every link k with shapes: the first of them meets the base at joint 1, but a
  // tool offset from that joint may still reach the column (CollisionChecker drops the pair only
  // where it touches in every sampled configuration, and then without a warning).
  std::vector<std::pair<int, int>> nonAdjacentLinkPairs() const;

  // World pose of every link frame; poses is resized to numLinks().
  virtual void linkPoses(const Eigen::Ref<const Eigen::VectorXd>& q, Poses& poses) const = 0;
  // Workspace positions of the control points, one column each (3 x numControlPoints()).
  virtual void controlPoints(const Eigen::Ref<const Eigen::VectorXd>& q,
                             Eigen::Matrix3Xd& points) const = 0;
  virtual int numControlPoints() const = 0;

  // An upper bound on how far any point of any link shape moves while q goes straight from a to b
  // (certified motion validation, Schwarzer, Saha and Latombe 2005): sum_j reach_j |b_j - a_j| for a
  // revolute chain, reach_j bounding the distance from joint j's axis to every point it moves.
  virtual double displacementBound(const Eigen::Ref<const Eigen::VectorXd>& a,
                                   const Eigen::Ref<const Eigen::VectorXd>& b) const;
  // The same bound per link (bounds resized to numLinks()): link k of a chain moves only by joints
  // 0..k, sum_{j <= k} reach_jk |b_j - a_j|, which also bounds its motion relative to any link a < k
  // (only joints a+1..k move it there). Without a chain reach every link gets displacementBound.
  void linkDisplacementBounds(const Eigen::Ref<const Eigen::VectorXd>& a,
                              const Eigen::Ref<const Eigen::VectorXd>& b, Eigen::VectorXd& bounds) const;
  const Eigen::VectorXd& jointReach() const { return joint_reach_; }
  // False only when no configuration brings any point of the robot into `box` (world frame): for a
  // chain, when the box lies beyond jointReach()[0] of the first joint's origin, which no joint moves;
  // true when the robot gives no bound. Obstacle sampling skips the obstacles no configuration touches.
  virtual bool mayReach(const Eigen::AlignedBox3d& box) const;
  // A configuration within the limits that places the robot at `point` (world frame), where a closed
  // form gives one (a point robot: the point itself); nullopt otherwise. Obstacle sampling roots a
  // tree at points drawn in the obstacle's bounding box this way before searching the whole space.
  virtual std::optional<Eigen::VectorXd> configurationAt(const Eigen::Vector3d& point) const;
  // How far any point of the robot may move over a straight motion of `length` in the weighted metric
  // (`scale`: the square roots of the metric weights): displacementBound in its worst direction, by
  // Cauchy-Schwarz length sqrt(sum_j reach_j^2 / scale_j^2) for a chain.
  virtual double stepDisplacement(const Eigen::VectorXd& scale, double length) const;

  // Throws std::invalid_argument naming the problem when q has the wrong size or is not finite.
  void checkConfiguration(const Eigen::Ref<const Eigen::VectorXd>& q, const char* where) const;

 protected:
  Robot(std::string name, Eigen::VectorXd lower, Eigen::VectorXd upper, int workspace_dim);
  // For a serial chain whose joint j turns link frame j (and everything after it) about an axis through
  // frame j's origin: origin_offset[k] is the constant distance between the origins of frames k - 1
  // and k (k >= 1). Then reach_j = max over k >= j of (sum of offsets j+1..k + the reach of link k's
  // shapes from frame k's origin). Call after the link shapes are set.
  void setChainReach(const std::vector<double>& origin_offset);
  std::string name_;
  Eigen::VectorXd lower_, upper_;
  int workspace_dim_;
  std::vector<std::vector<Shape>> link_shapes_;
  std::vector<Shape> base_shapes_;  // world frame
  Eigen::VectorXd joint_reach_;
  Eigen::MatrixXd link_reach_;  // (link k, joint j): reach of joint j over link k's points, 0 for j > k
};

}  // namespace svmp::robots
