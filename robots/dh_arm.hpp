#pragma once
// Serial arm described by a modified (Craig) Denavit-Hartenberg table: frame i is reached from frame
// i-1 by RotX(alpha_{i-1}) TransX(a_{i-1}) RotZ(theta_i + offset_i) TransZ(d_i). Presets: the CRS-F3 of
// thesis Table 4.3 (ch. 4.2.2) and the Franka Emika Panda. Link i's shapes live in frame i; by default
// each link is a capsule along the segment(s) from joint i to joint i+1 (or to the flange for the last),
// and the base is one along the segment from the base frame to joint 1 (the Panda's 0.333 m column),
// with joint 1's radius.
// An optional tool (thesis Fig 4.12: the cubic frame) is a set of shapes in the flange frame, part of
// the last link.
#include "robots/robot.hpp"

namespace svmp::robots {

struct DhRow {
  double a = 0;       // a_{i-1}
  double alpha = 0;   // alpha_{i-1}
  double d = 0;       // d_i
  double offset = 0;  // added to the joint variable theta_i
};

struct DhArmSpec {
  std::string name = "dh_arm";
  std::vector<DhRow> rows;
  Eigen::VectorXd lower, upper;
  std::vector<double> link_radius;  // one per joint; capsule radius of the default link shapes
  // Flange frame = last frame * RotX(flange.alpha) TransX(flange.a) TransZ(flange.d) (no joint).
  DhRow flange;
  Eigen::Isometry3d base = Eigen::Isometry3d::Identity();
  std::vector<Shape> tool;          // in the flange frame
  Eigen::Vector3d tool_tip = Eigen::Vector3d::Zero();  // control point, in the flange frame
};

class DhArm final : public Robot {
 public:
  explicit DhArm(DhArmSpec spec);

  const DhArmSpec& spec() const { return spec_; }
  void linkPoses(const Eigen::Ref<const Eigen::VectorXd>& q, Poses& poses) const override;
  Eigen::Isometry3d flangePose(const Eigen::Ref<const Eigen::VectorXd>& q) const;
  // Control points: the distinct moving joint origins, the tool tip, then both ends of the longest
  // axis of each tool box (Das & Yip 2019 sec. III-A place points at joint origins; points off the
  // last axis make the last joint observable).
  void controlPoints(const Eigen::Ref<const Eigen::VectorXd>& q, Eigen::Matrix3Xd& points) const override;
  int numControlPoints() const override {
    return static_cast<int>(moving_origins_.size() + 1 + tool_points_.size());
  }

  // Closed-form position IK of the first three joints for the elbow structure of the CRS-F3
  // (alpha0 = 0, a0 = 0, alpha1 = +-pi/2, alpha2 = 0, d2 = d3 = 0, a3 = 0, alpha3 = +-pi/2), the
  // thesis' simplified model of ch. 2.3: configurations that put the point at distance s along link
  // `link` (1: shoulder offset a1, 2: upper arm a2, 3: forearm d4; 1-based like the table) on target.
  // Shoulder left/right and elbow up/down give up to four solutions; joints beyond 3 copy `seed`.
  // Throws std::logic_error when the table does not have that structure (hasElbowStructure).
  bool hasElbowStructure() const;
  std::vector<Eigen::VectorXd> solvePointOnLinkFirstThree(
      int link, double s, const Eigen::Vector3d& target,
      const Eigen::Ref<const Eigen::VectorXd>& seed) const;
  // World position of the point at distance s along the axis of link 1..3 (same links as above).
  Eigen::Vector3d pointOnLinkFirstThree(const Eigen::Ref<const Eigen::VectorXd>& q, int link,
                                        double s) const;

 private:
  DhArmSpec spec_;
  std::vector<int> moving_origins_;  // frames whose origin is a distinct, moving joint origin
  std::vector<double> cos_alpha_, sin_alpha_;  // per DH row, then the flange (DhFrame in dh_arm.cpp)
  // Control points after the tip, in the flange frame: both ends of each tool box's longest axis. The
  // joint origins and the tip lie on the last joint's axis, so without them the FK kernel cannot see
  // the last joint turn the tool (a hand wider than it is deep).
  std::vector<Eigen::Vector3d> tool_points_;
};

// Thesis Table 4.3 with `joints` (3 or 6) joints; 3 gives the simplified model of ch. 2.3 whose last
// link is the forearm up to the wrist centre. Joint limits: see docs/scenarios.md (assumed).
DhArmSpec crsF3Spec(int joints = 6);
// Franka Emika Panda (modified DH and limits from the maker's documentation), flange d = 0.107.
DhArmSpec pandaSpec();

}  // namespace svmp::robots
