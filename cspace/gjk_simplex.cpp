#include "cspace/gjk_simplex.hpp"

#include <Eigen/Geometry>  // cross products
#include <Eigen/LU>        // determinants of fixed-size matrices
#include <algorithm>
#include <cmath>
#include <limits>

namespace svmp::cspace::gjk {

bool Simplex::has(const Eigen::Vector3d& w) const {
  for (int i = 0; i < n; ++i)
    if ((p[i] - w).squaredNorm() <= 1e-28 * (1 + w.squaredNorm())) return true;
  return false;
}

namespace {

// Below this share of its bound (Hadamard's, Lagrange's) a determinant, a squared area or a volume
// counts as zero: the points are then dependent to within rounding.
constexpr double kDegenerate = 1e-12;

// The point of the affine hull of the points idx[0..K] closest to the origin, with its barycentric
// weights; false when the points are affinely dependent (a smaller subset covers that case). The
// normal equations (Gram matrix of the edges from the first point) are solved by Cramer's rule: at
// most 3x3, where a general factorisation cost most of a distance query.
template <int K>
bool projectOrigin(const Simplex& s, const int* idx, Eigen::Vector3d& x, double* w) {
  Eigen::Matrix<double, 3, K> e;
  for (int i = 0; i < K; ++i) e.col(i) = s.p[idx[i + 1]] - s.p[idx[0]];
  const Eigen::Matrix<double, K, K> g = e.transpose() * e;
  const Eigen::Matrix<double, K, 1> r = -e.transpose() * s.p[idx[0]];
  const double det = g.determinant(), scale = g.diagonal().prod();
  if (!(std::abs(det) > kDegenerate * scale)) return false;
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

// Keeps the points of s whose bit is set in mask, in order.
void keep(Simplex& s, int mask) {
  Simplex kept;
  for (int i = 0; i < s.n; ++i)
    if (mask & (1 << i)) kept.p[kept.n++] = s.p[i];
  s = kept;
}

// The closest point of segment (a, b), indices of s; mask gets the points of its region. False when
// the segment has no length.
bool closestOnSegment(const Simplex& s, int a, int b, Eigen::Vector3d& x, int& mask) {
  const Eigen::Vector3d ab = s.p[b] - s.p[a];
  const double length2 = ab.squaredNorm(), t = -s.p[a].dot(ab);
  if (!(length2 > kDegenerate * s.p[a].squaredNorm())) return false;
  if (t <= 0) {
    x = s.p[a], mask = 1 << a;
  } else if (t >= length2) {
    x = s.p[b], mask = 1 << b;
  } else {
    x = s.p[a] + (t / length2) * ab, mask = (1 << a) | (1 << b);
  }
  return true;
}

// Ericson's ClosestPtPointTriangle with the point at the origin: vertex, edge and face regions by
// the signs of dot products, in that order. False when the triangle has no area.
bool closestOnTriangle(const Simplex& s, int ia, int ib, int ic, Eigen::Vector3d& x, int& mask) {
  const Eigen::Vector3d &a = s.p[ia], &b = s.p[ib], &c = s.p[ic];
  const Eigen::Vector3d ab = b - a, ac = c - a;
  const double area2 = ab.cross(ac).squaredNorm();
  if (!(area2 > kDegenerate * ab.squaredNorm() * ac.squaredNorm())) return false;
  const double d1 = -ab.dot(a), d2 = -ac.dot(a);
  if (d1 <= 0 && d2 <= 0) return x = a, mask = 1 << ia, true;
  const double d3 = -ab.dot(b), d4 = -ac.dot(b);
  if (d3 >= 0 && d4 <= d3) return x = b, mask = 1 << ib, true;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return x = a + (d1 / (d1 - d3)) * ab, mask = (1 << ia) | (1 << ib), true;
  const double d5 = -ab.dot(c), d6 = -ac.dot(c);
  if (d6 >= 0 && d5 <= d6) return x = c, mask = 1 << ic, true;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return x = a + (d2 / (d2 - d6)) * ac, mask = (1 << ia) | (1 << ic), true;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return x = b + w * (c - b), mask = (1 << ib) | (1 << ic), true;
  }
  // Inside the face: va + vb + vc is the squared area (Lagrange's identity), bounded away from 0.
  const double v = vb / area2, w = vc / area2;
  x = a + v * ab + w * ac, mask = (1 << ia) | (1 << ib) | (1 << ic);
  return true;
}

// Ericson's ClosestPtPointTetrahedron: the closest point lies on a face whose plane has the origin
// on the outer side; none such means the origin is inside. False when the tetrahedron is flat.
bool closestOnTetrahedron(const Simplex& s, Eigen::Vector3d& x, int& mask) {
  static constexpr int kFaces[4][4] = {{0, 1, 2, 3}, {0, 2, 3, 1}, {0, 3, 1, 2}, {1, 3, 2, 0}};
  double best = std::numeric_limits<double>::infinity();
  bool outside_any = false;
  for (const auto& f : kFaces) {
    const Eigen::Vector3d &a = s.p[f[0]], &d = s.p[f[3]];
    const Eigen::Vector3d normal = (s.p[f[1]] - a).cross(s.p[f[2]] - a);
    const double side_d = normal.dot(d - a), side_origin = -normal.dot(a);
    if (!(std::abs(side_d) > kDegenerate * normal.norm() * (d - a).norm())) return false;
    if (!(side_origin * side_d < 0)) continue;
    outside_any = true;
    Eigen::Vector3d y;
    int m = 0;
    if (!closestOnTriangle(s, f[0], f[1], f[2], y, m)) return false;
    if (y.squaredNorm() < best) best = y.squaredNorm(), x = y, mask = m;
  }
  if (!outside_any) x.setZero(), mask = 15;
  return true;
}

}  // namespace

// Every face is tried (at most 15): the closest point lies inside some face, where it is that face's
// projection, and every projection with non-negative weights is a point of the hull.
Eigen::Vector3d closestToOriginByFaces(Simplex& s) {
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
  keep(s, best_mask);
  return closest;
}

Eigen::Vector3d closestToOrigin(Simplex& s) {
  Eigen::Vector3d x = s.p[0];
  int mask = 1;
  bool ok = true;
  switch (s.n) {
    case 1:
      return x;
    case 2:
      ok = closestOnSegment(s, 0, 1, x, mask);
      break;
    case 3:
      ok = closestOnTriangle(s, 0, 1, 2, x, mask);
      break;
    default:
      ok = closestOnTetrahedron(s, x, mask);
      break;
  }
  if (!ok || !x.allFinite()) return closestToOriginByFaces(s);
  keep(s, mask);
  return x;
}

}  // namespace svmp::cspace::gjk
