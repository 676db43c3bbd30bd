#pragma once
// The FCL geometry of one of our primitives, for tests that compare with FCL's own answers.
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>

#include <memory>

#include "robots/shape.hpp"

namespace svmp::cspace::test {

inline std::shared_ptr<fcl::CollisionGeometryd> fclGeometry(const robots::Shape& s) {
  switch (s.kind) {
    case robots::ShapeKind::kBox:
      return std::make_shared<fcl::Boxd>(s.dims);
    case robots::ShapeKind::kSphere:
      return std::make_shared<fcl::Sphered>(s.dims.x());
    case robots::ShapeKind::kCapsule:
      return std::make_shared<fcl::Capsuled>(s.dims.x(), s.dims.y());
    default:
      return std::make_shared<fcl::Cylinderd>(s.dims.x(), s.dims.y());
  }
}

}  // namespace svmp::cspace::test
