#include "robots/shape.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace svmp::robots {

Shape Shape::box(const Eigen::Vector3d& sides, const Eigen::Isometry3d& pose) {
  return Shape{ShapeKind::kBox, sides, pose};
}

Shape Shape::sphere(double radius, const Eigen::Isometry3d& pose) {
  return Shape{ShapeKind::kSphere, Eigen::Vector3d(radius, 0, 0), pose};
}

Shape Shape::cylinder(double radius, double length, const Eigen::Isometry3d& pose) {
  return Shape{ShapeKind::kCylinder, Eigen::Vector3d(radius, length, 0), pose};
}

Shape Shape::capsule(double radius, double length, const Eigen::Isometry3d& pose) {
  return Shape{ShapeKind::kCapsule, Eigen::Vector3d(radius, length, 0), pose};
}

Shape Shape::capsuleBetween(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double radius) {
  const Eigen::Vector3d axis = b - a;
  const double length = axis.norm();
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = 0.5 * (a + b);
  if (length > 0) {
    pose.linear() =
        Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), axis / length).toRotationMatrix();
  }
  // A zero-length capsule is a sphere; FCL handles a capsule of length 0 as one.
  return capsule(radius, length, pose);
}

double Shape::reach() const {
  double extent = 0;  // from the shape's own centre
  switch (kind) {
    case ShapeKind::kBox: extent = 0.5 * dims.norm(); break;
    case ShapeKind::kSphere: extent = dims.x(); break;
    case ShapeKind::kCylinder: extent = std::hypot(dims.x(), 0.5 * dims.y()); break;
    case ShapeKind::kCapsule: extent = dims.x() + 0.5 * dims.y(); break;
  }
  return pose.translation().norm() + extent;
}

Eigen::AlignedBox3d Shape::boundsAt(const Eigen::Isometry3d& at) const {
  const Eigen::Matrix3d rotation = at.linear().cwiseAbs();
  Eigen::Vector3d half = Eigen::Vector3d::Zero();
  switch (kind) {
    case ShapeKind::kBox: half = rotation * (0.5 * dims); break;
    case ShapeKind::kSphere: half.setConstant(dims.x()); break;
    case ShapeKind::kCylinder: half = rotation * Eigen::Vector3d(dims.x(), dims.x(), 0.5 * dims.y()); break;
    case ShapeKind::kCapsule: half = rotation.col(2) * (0.5 * dims.y()) + Eigen::Vector3d::Constant(dims.x()); break;
  }
  return {at.translation() - half, at.translation() + half};
}

double Shape::thickness() const {
  switch (kind) {
    case ShapeKind::kBox: return dims.minCoeff();
    case ShapeKind::kSphere:
    case ShapeKind::kCapsule: return 2 * dims.x();
    case ShapeKind::kCylinder: return std::min(2 * dims.x(), dims.y());
  }
  return 0;
}

const char* shapeKindName(ShapeKind kind) {
  switch (kind) {
    case ShapeKind::kBox: return "box";
    case ShapeKind::kSphere: return "sphere";
    case ShapeKind::kCylinder: return "cylinder";
    case ShapeKind::kCapsule: return "capsule";
  }
  return "?";
}

std::string Shape::validate() const {
  std::ostringstream err;
  auto positive = [](double v) { return std::isfinite(v) && v > 0; };
  switch (kind) {
    case ShapeKind::kBox:
      if (!positive(dims.x()) || !positive(dims.y()) || !positive(dims.z()))
        err << "box sides must be positive and finite, got [" << dims.transpose() << "]";
      break;
    case ShapeKind::kSphere:
      if (!positive(dims.x())) err << "sphere radius must be positive, got " << dims.x();
      break;
    case ShapeKind::kCylinder:
    case ShapeKind::kCapsule:
      if (!positive(dims.x())) err << shapeKindName(kind) << " radius must be positive, got " << dims.x();
      else if (!std::isfinite(dims.y()) || dims.y() < 0 || (kind == ShapeKind::kCylinder && dims.y() == 0))
        err << shapeKindName(kind) << " length must be positive, got " << dims.y();
      break;
  }
  if (!pose.matrix().allFinite()) err << (err.tellp() > 0 ? "; " : "") << "pose is not finite";
  return err.str();
}

bool Shape::contains(const Eigen::Vector3d& p_frame) const {
  const Eigen::Vector3d p = pose.inverse() * p_frame;
  switch (kind) {
    case ShapeKind::kBox:
      return (p.cwiseAbs() - 0.5 * dims).maxCoeff() <= 0;
    case ShapeKind::kSphere:
      return p.norm() <= dims.x();
    case ShapeKind::kCylinder:
      return std::abs(p.z()) <= 0.5 * dims.y() && p.head<2>().norm() <= dims.x();
    case ShapeKind::kCapsule: {
      const double z = std::clamp(p.z(), -0.5 * dims.y(), 0.5 * dims.y());
      return (p - Eigen::Vector3d(0, 0, z)).norm() <= dims.x();
    }
  }
  return false;
}

}  // namespace svmp::robots
