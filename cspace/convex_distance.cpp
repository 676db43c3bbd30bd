#include "cspace/convex_distance.hpp"

#include "cspace/gjk_simplex.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

namespace svmp::cspace {
namespace {

using gjk::Simplex;
using gjk::closestToOrigin;

double sign(double x) { return x < 0 ? -1.0 : 1.0; }

}  // namespace

Eigen::Vector3d supportPoint(const robots::Shape& s, const Eigen::Isometry3d& pose,
                             const Eigen::Vector3d& u) {
  const Eigen::Vector3d m = pose.linear().transpose() * u;  // u in the shape's frame
  const double un = u.norm();
  Eigen::Vector3d local = Eigen::Vector3d::Zero();
  switch (s.kind) {
    case robots::ShapeKind::kBox:
      local = 0.5 * Eigen::Vector3d(sign(m.x()) * s.dims.x(), sign(m.y()) * s.dims.y(),
                                    sign(m.z()) * s.dims.z());
      break;
    case robots::ShapeKind::kSphere:
      if (un > 0) local = s.dims.x() * m / un;
      break;
    case robots::ShapeKind::kCapsule:
      local = Eigen::Vector3d(0, 0, sign(m.z()) * 0.5 * s.dims.y());
      if (un > 0) local += s.dims.x() * m / un;
      break;
    case robots::ShapeKind::kCylinder: {
      const double radial = m.head<2>().norm();
      local.z() = sign(m.z()) * 0.5 * s.dims.y();
      if (radial > 0) local.head<2>() = s.dims.x() * m.head<2>() / radial;
      break;
    }
  }
  return pose * local;
}

double separationAlong(const robots::Shape& a, const Eigen::Isometry3d& pa, const robots::Shape& b,
                       const Eigen::Isometry3d& pb, const Eigen::Vector3d& v) {
  const double norm = v.norm();
  if (!(norm > 0) || !std::isfinite(norm)) return -std::numeric_limits<double>::infinity();
  // The point of A - B farthest along -v: s_A(-v) - s_B(v).
  const Eigen::Vector3d w = supportPoint(a, pa, -v) - supportPoint(b, pb, v);
  return v.dot(w) / norm;
}

namespace {

// A sphere or a capsule is its core (a point, a segment) grown by its radius: GJK runs on the cores,
// whose difference with a box is a polytope, so it ends exactly in a few iterations, where on the
// round shapes it only converges (slowly when they nearly touch). The separation along any
// direction is the cores' less both radii.
robots::Shape core(const robots::Shape& s, double& radius) {
  if (s.kind != robots::ShapeKind::kSphere && s.kind != robots::ShapeKind::kCapsule) return s;
  radius += s.dims.x();
  robots::Shape c = s;
  c.dims.x() = 0;
  return c;
}

// A sphere against a box or a cylinder in closed form: the plane normal to the centre's offset from
// its nearest point of the other shape gives the exact distance. GJK only converges on a cylinder's
// round side, and on a long one (a pole 10,000 long, 0.05 in radius) stopped undecided where FCL then
// reported a point 3e-5 away as touching. Empty unless the pair is a sphere and a box or cylinder.
std::optional<double> sphereSeparation(const robots::Shape& a, const Eigen::Isometry3d& pa,
                                       const robots::Shape& b, const Eigen::Isometry3d& pb) {
  const auto other = [](const robots::Shape& s) {
    return s.kind == robots::ShapeKind::kBox || s.kind == robots::ShapeKind::kCylinder;
  };
  const bool a_sphere = a.kind == robots::ShapeKind::kSphere && other(b);
  if (!a_sphere && !(b.kind == robots::ShapeKind::kSphere && other(a))) return {};
  const robots::Shape& solid = a_sphere ? b : a;
  const Eigen::Isometry3d& solid_pose = a_sphere ? pb : pa;
  const Eigen::Vector3d centre = solid_pose.inverse() * (a_sphere ? pa : pb).translation();
  Eigen::Vector3d nearest;
  if (solid.kind == robots::ShapeKind::kBox) {
    const Eigen::Vector3d half = 0.5 * solid.dims;
    nearest = centre.cwiseMax(-half).cwiseMin(half);
  } else {
    const double radial = centre.head<2>().norm(), half_length = 0.5 * solid.dims.y();
    nearest.head<2>() = radial > solid.dims.x() ? (solid.dims.x() / radial) * centre.head<2>()
                                                : Eigen::Vector2d(centre.head<2>());
    nearest.z() = std::clamp(centre.z(), -half_length, half_length);
  }
  const Eigen::Vector3d offset = centre - nearest;
  if (!(offset.squaredNorm() > 0)) return 0.0;  // the centre inside: they overlap
  const Eigen::Vector3d v = solid_pose.linear() * offset;  // from the solid towards the sphere
  return separationAlong(a, pa, b, pb, a_sphere ? v : Eigen::Vector3d(-v));
}

// Two boxes by the separating-axis test (Gottschalk, Lin and Manocha, OBBTree, 1996; Ericson 4.4.1):
// they are apart exactly when one of the 15 axes (3 face normals each, 9 edge-pair cross products)
// separates their projections, so the answer is exact where GJK needs up to four iterations (the
// planar arms' links inside an obstacle). The small term added to |R| on the edge-pair axes keeps a
// near-zero cross product of parallel edges from separating them on rounding (parallel edges are
// then separated, if at all, by a face axis). The face axes take no such term: it would widen
// every box by 1e-12 of the other's size, 1.5e-8 for a 1e4 box, where the certifier proves
// clearances down to 1e-6 of the resolution, and check() would reject configurations it proves.
bool boxesOverlap(const robots::Shape& a, const Eigen::Isometry3d& pa, const robots::Shape& b,
                  const Eigen::Isometry3d& pb) {
  const Eigen::Vector3d ea = 0.5 * a.dims, eb = 0.5 * b.dims;
  const Eigen::Matrix3d r = pa.linear().transpose() * pb.linear();  // b's axes in a's frame
  Eigen::Matrix3d abs_r = r.cwiseAbs();
  const Eigen::Vector3d t = pa.linear().transpose() * (pb.translation() - pa.translation());
  for (int i = 0; i < 3; ++i)
    if (std::abs(t[i]) > ea[i] + abs_r.row(i).dot(eb)) return false;
  for (int j = 0; j < 3; ++j)
    if (std::abs(t.dot(r.col(j))) > abs_r.col(j).dot(ea) + eb[j]) return false;
  abs_r.array() += 1e-12;
  for (int i = 0; i < 3; ++i) {
    const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
    for (int j = 0; j < 3; ++j) {
      const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
      const double ra = ea[i1] * abs_r(i2, j) + ea[i2] * abs_r(i1, j);
      const double rb = eb[j1] * abs_r(i, j2) + eb[j2] * abs_r(i, j1);
      if (std::abs(t[i2] * r(i1, j) - t[i1] * r(i2, j)) > ra + rb) return false;
    }
  }
  return true;
}

}  // namespace

double distanceLowerBound(const robots::Shape& a_shape, const Eigen::Isometry3d& pa,
                          const robots::Shape& b_shape, const Eigen::Isometry3d& pb,
                          const Eigen::Vector3d& hint, double rel_gap, double enough) {
  if (const auto exact = sphereSeparation(a_shape, pa, b_shape, pb)) return *exact;
  double margin = 0;
  const robots::Shape a = core(a_shape, margin), b = core(b_shape, margin);
  Eigen::Vector3d v = hint;
  if (!(v.norm() > 0) || !v.allFinite()) v = pa.translation() - pb.translation();
  if (!(v.norm() > 0)) v = Eigen::Vector3d::UnitX();
  double best = -std::numeric_limits<double>::infinity();  // of the cores
  Simplex s;
  for (int iteration = 0; iteration < 64; ++iteration) {
    const Eigen::Vector3d w = supportPoint(a, pa, -v) - supportPoint(b, pb, v);
    const double norm = v.norm();
    best = std::max(best, v.dot(w) / norm);
    if (best - margin >= enough) break;
    // |v| bounds the cores' distance from above once v is a point of the simplex (the hint need not
    // be); within the margin the shapes may touch, and the bound is <= 0 whatever follows.
    if (s.n > 0 && (norm - best <= rel_gap * (norm - margin) || norm <= margin)) break;
    if (s.has(w) || s.n == 4) break;  // no progress possible (numerical stall)
    s.p[s.n++] = w;
    v = closestToOrigin(s);
    // The origin in the hull (or on it): the cores overlap; best is then <= 0 as well.
    if (v.squaredNorm() <= 1e-30 || s.n == 4) break;
  }
  return best - margin;
}

std::optional<bool> intersects(const robots::Shape& a_shape, const Eigen::Isometry3d& pa,
                               const robots::Shape& b_shape, const Eigen::Isometry3d& pb) {
  if (const auto exact = sphereSeparation(a_shape, pa, b_shape, pb)) return *exact <= 0;
  if (a_shape.kind == robots::ShapeKind::kBox && b_shape.kind == robots::ShapeKind::kBox)
    return boxesOverlap(a_shape, pa, b_shape, pb);
  double margin = 0;
  const robots::Shape a = core(a_shape, margin), b = core(b_shape, margin);
  Eigen::Vector3d v = pa.translation() - pb.translation();
  if (!(v.squaredNorm() > 0)) v = Eigen::Vector3d::UnitX();
  Simplex s;
  for (int iteration = 0; iteration < 64; ++iteration) {
    const Eigen::Vector3d w = supportPoint(a, pa, -v) - supportPoint(b, pb, v);
    // A plane separating the cores by more than the radii: apart.
    if (v.dot(w) > margin * v.norm()) return false;
    if (s.has(w)) return std::nullopt;  // stalled undecided
    s.p[s.n++] = w;
    v = closestToOrigin(s);
    // A point of the cores' difference within the radii of the origin (or the origin enclosed):
    // two points of the cores that close, so the shapes touch.
    if (s.n == 4 || v.squaredNorm() <= margin * margin + 1e-30) return true;
  }
  return std::nullopt;
}

}  // namespace svmp::cspace
