#pragma once
// Collision shapes of robot links and obstacles. Only FCL primitives are used: FCL meshes do not detect
// one body entirely inside another, and obstacle sampling (thesis ch. 3.1) lives inside obstacles.
// Thread safety: Shape is a plain value.
#include <Eigen/Geometry>
#include <string>

namespace svmp::robots {

enum class ShapeKind { kBox, kSphere, kCylinder, kCapsule };

struct Shape {
  ShapeKind kind = ShapeKind::kBox;
  // kBox: full side lengths (x, y, z). kSphere: (radius, -, -).
  // kCylinder, kCapsule: (radius, length along the local z axis, -); a capsule's length excludes its caps.
  Eigen::Vector3d dims = Eigen::Vector3d::Zero();
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  // in the frame the shape is attached to

  static Shape box(const Eigen::Vector3d& sides, const Eigen::Isometry3d& pose = Eigen::Isometry3d::Identity());
  static Shape sphere(double radius, const Eigen::Isometry3d& pose = Eigen::Isometry3d::Identity());
  static Shape cylinder(double radius, double length,
                        const Eigen::Isometry3d& pose = Eigen::Isometry3d::Identity());
  static Shape capsule(double radius, double length,
                       const Eigen::Isometry3d& pose = Eigen::Isometry3d::Identity());
  // A capsule whose axis runs from a to b (frame coordinates); used for DH links.
  static Shape capsuleBetween(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double radius);

  // Empty string when the dimensions are positive and finite, else what is wrong.
  std::string validate() const;
  // True when point p (frame coordinates) lies inside or on the shape.
  bool contains(const Eigen::Vector3d& p) const;
  // The largest distance from the origin of the frame the shape is attached to, to any of its points.
  double reach() const;
  // An axis-aligned box holding the shape, in the frame it is attached to (not the tightest for a
  // rotated cylinder: its bounding box's).
  Eigen::AlignedBox3d bounds() const { return boundsAt(pose); }
  // The same with the shape placed at `at` instead of its own pose (a link shape's world pose).
  Eigen::AlignedBox3d boundsAt(const Eigen::Isometry3d& at) const;
  // The smallest width across the shape: a box's shortest side, a sphere's or capsule's diameter, the
  // smaller of a cylinder's diameter and length.
  double thickness() const;
};

const char* shapeKindName(ShapeKind kind);

}  // namespace svmp::robots
