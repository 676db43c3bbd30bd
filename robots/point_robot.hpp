#pragma once
// A point robot in 2D or 3D (thesis ch. 3.4, Figs 3.5 and 3.7): the configuration is the position.
// It is modelled as a sphere of tiny radius so FCL answers collision and distance queries for it.
#include "robots/robot.hpp"

namespace svmp::robots {

class PointRobot final : public Robot {
 public:
  PointRobot(const Eigen::VectorXd& lower, const Eigen::VectorXd& upper, double radius = 1e-6);
  double radius() const { return radius_; }
  void linkPoses(const Eigen::Ref<const Eigen::VectorXd>& q, Poses& poses) const override;
  void controlPoints(const Eigen::Ref<const Eigen::VectorXd>& q, Eigen::Matrix3Xd& points) const override;
  int numControlPoints() const override { return 1; }
  // Whether the box meets the bounds (z = 0 in 2-D) grown by the radius.
  bool mayReach(const Eigen::AlignedBox3d& box) const override;
  // The point's first dof() coordinates when they are within the limits (in 2-D: the point's
  // projection onto z = 0, where the robot moves).
  std::optional<Eigen::VectorXd> configurationAt(const Eigen::Vector3d& point) const override;
  // Exact: the robot translates by b - a.
  double displacementBound(const Eigen::Ref<const Eigen::VectorXd>& a,
                           const Eigen::Ref<const Eigen::VectorXd>& b) const override {
    return (b - a).norm();
  }
  // Exact: the longest b - a of that length lies along the axis of least weight.
  double stepDisplacement(const Eigen::VectorXd& scale, double length) const override {
    return length / scale.minCoeff();
  }

 private:
  double radius_;
};

}  // namespace svmp::robots
