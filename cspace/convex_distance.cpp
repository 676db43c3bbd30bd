#include "cspace/convex_distance.hpp"

#include <Eigen/LU>  // determinant of fixed-size matrices
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>

namespace svmp::cspace {
namespace {

double sign(double x) { return x < 0 ? -1.0 : 1.0; }

// Up to four points of A - B (GJK's simplex).
struct Simplex {
  std::array<Eigen::Vector3d, 4> p;
  int n = 0;
  // Whether w is already a point (to rounding): GJK has stalled, no new support point to add.
  bool has(const Eigen::Vector3d& w) const {
    for (int i = 0; i < n; ++i)
      if ((p[i] - w).squaredNorm() <= 1e-28 * (1 + w.squaredNorm())) return true;
    return false;
  }
};

// The point of the affine hull of the points idx[0..K] closest to the origin, with its barycentric
// weights; false when the points are affinely dependent (a smaller subset covers that case). The
// normal equations (Gram matrix of the edges from the first point) are solved by Cramer's rule:
// at most 3x3, where a general factorisation cost most of a distance query.
template <int K>
bool projectOrigin(const Simplex& s, const int* idx, Eigen::Vector3d& x, double* w) {
  Eigen::Matrix<double, 3, K> e;
  for (int i = 0; i < K; ++i) e.col(i) = s.p[idx[i + 1]] - s.p[idx[0]];
  const Eigen::Matrix<double, K, K> g = e.transpose() * e;
  const Eigen::Matrix<double, K, 1> r = -e.transpose() * s.p[idx[0]];
  // Singular when the determinant is below 1e-12 of the product of the diagonal (Hadamard's bound
  // on it): the edges are then dependent to within rounding.
  const double det = g.determinant(), scale = g.diagonal().prod();
  if (!(std::abs(det) > 1e-12 * scale)) return false;
  Eigen::Matrix<double, K, 1> lambda;
  for (int i = 0; i < K; ++i) {
    Eigen::Matrix<double, K, K> gi = g;
    gi.col(i) = r;
    lambda[i] = gi.determinant() / det;
  }
  x = s.p[idx[0]] + e * lambda;
  w[0] = 1 - lambda.sum();
  for (int i = 0; i < K; ++i) w[i + 1] = lambda[i];
  return true;
}

// The point of conv(s) closest to the origin; s keeps only the points of the face holding it. Every
// face is tried (at most 15): the closest point lies inside some face, where it is that face's
// projection, and every projection with non-negative weights is a point of the hull.
Eigen::Vector3d closestToOrigin(Simplex& s) {
  double best = std::numeric_limits<double>::infinity();
  Eigen::Vector3d closest = s.p[0];
  int best_mask = 1;
  for (int mask = 1; mask < (1 << s.n); ++mask) {
    int idx[4], k = 0;
    for (int i = 0; i < s.n; ++i)
      if (mask & (1 << i)) idx[k++] = i;
    Eigen::Vector3d x;
    double w[4] = {1, 0, 0, 0};
    bool ok = true;
    switch (k) {
      case 1:
        x = s.p[idx[0]];
        break;
      case 2:
        ok = projectOrigin<1>(s, idx, x, w);
        break;
      case 3:
        ok = projectOrigin<2>(s, idx, x, w);
        break;
      default:
        ok = projectOrigin<3>(s, idx, x, w);
        break;
    }
    if (!ok || *std::min_element(w, w + k) < 0 || !(x.squaredNorm() < best)) continue;
    best = x.squaredNorm();
    closest = x;
    best_mask = mask;
  }
  Simplex kept;
  for (int i = 0; i < s.n; ++i)
    if (best_mask & (1 << i)) kept.p[kept.n++] = s.p[i];
  s = kept;
  return closest;
}

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

// A sphere against a box in closed form: the plane normal to the centre's offset from its nearest
// point of the box gives the exact distance. Empty unless the pair is a sphere and a box.
std::optional<double> sphereBoxSeparation(const robots::Shape& a, const Eigen::Isometry3d& pa,
                                          const robots::Shape& b, const Eigen::Isometry3d& pb) {
  const bool a_sphere = a.kind == robots::ShapeKind::kSphere && b.kind == robots::ShapeKind::kBox;
  if (!a_sphere && !(b.kind == robots::ShapeKind::kSphere && a.kind == robots::ShapeKind::kBox)) return {};
  const Eigen::Isometry3d& box_pose = a_sphere ? pb : pa;
  const Eigen::Vector3d centre = box_pose.inverse() * (a_sphere ? pa : pb).translation();
  const Eigen::Vector3d half = 0.5 * (a_sphere ? b : a).dims;
  const Eigen::Vector3d offset = centre - centre.cwiseMax(-half).cwiseMin(half);
  if (!(offset.squaredNorm() > 0)) return 0.0;  // the centre inside the box: they overlap
  const Eigen::Vector3d v = box_pose.linear() * offset;  // from the box towards the sphere
  return separationAlong(a, pa, b, pb, a_sphere ? v : Eigen::Vector3d(-v));
}

}  // namespace

double distanceLowerBound(const robots::Shape& a_shape, const Eigen::Isometry3d& pa,
                          const robots::Shape& b_shape, const Eigen::Isometry3d& pb,
                          const Eigen::Vector3d& hint, double rel_gap) {
  if (const auto exact = sphereBoxSeparation(a_shape, pa, b_shape, pb)) return *exact;
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
  if (const auto exact = sphereBoxSeparation(a_shape, pa, b_shape, pb)) return *exact <= 0;
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
