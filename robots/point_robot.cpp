#include "robots/point_robot.hpp"

#include <stdexcept>

namespace svmp::robots {

PointRobot::PointRobot(const Eigen::VectorXd& lower, const Eigen::VectorXd& upper, double radius)
    : Robot(lower.size() == 2 ? "point2d" : "point3d", lower, upper, static_cast<int>(lower.size())),
      radius_(radius) {
  if (lower.size() != 2 && lower.size() != 3)
    throw std::invalid_argument("point robot: dimension must be 2 or 3, got " +
                                std::to_string(lower.size()));
  if (!(radius > 0)) throw std::invalid_argument("point robot: radius must be positive");
  link_shapes_ = {{Shape::sphere(radius)}};
}

void PointRobot::linkPoses(const Eigen::Ref<const Eigen::VectorXd>& q, Poses& poses) const {
  poses.resize(1);
  poses[0].setIdentity();
  poses[0].translation().head(q.size()) = q;
}

bool PointRobot::mayReach(const Eigen::AlignedBox3d& box) const {
  Eigen::Vector3d low = Eigen::Vector3d::Zero(), high = Eigen::Vector3d::Zero();
  low.head(dof()) = lowerLimits();
  high.head(dof()) = upperLimits();
  const Eigen::Vector3d grow = Eigen::Vector3d::Constant(radius_);
  return box.intersects(Eigen::AlignedBox3d(low - grow, high + grow));
}

std::optional<Eigen::VectorXd> PointRobot::configurationAt(const Eigen::Vector3d& point) const {
  const Eigen::VectorXd q = point.head(dof());
  if ((q.array() < lowerLimits().array()).any() || (q.array() > upperLimits().array()).any())
    return std::nullopt;
  return q;
}

void PointRobot::controlPoints(const Eigen::Ref<const Eigen::VectorXd>& q,
                               Eigen::Matrix3Xd& points) const {
  points.setZero(3, 1);
  points.col(0).head(q.size()) = q;
}

}  // namespace svmp::robots
