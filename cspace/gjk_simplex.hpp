#pragma once
// GJK's simplex (up to four points of the Minkowski difference A - B) and the step that reduces it
// to the face holding its point closest to the origin (cspace/convex_distance.cpp). The fast path
// tests the Voronoi regions of the segment, triangle and tetrahedron (Ericson, Real-Time Collision
// Detection, 2005, 5.1.2, 5.1.5 and 5.1.6): a few dot products where trying every face (up to 15
// projections, each a small determinant solve) was a fifth of SVMP's time on the thesis' arms,
// whose samples lie inside obstacles and so run GJK to a full tetrahedron. A degenerate simplex
// (collinear, coplanar to rounding) goes to the every-face search, which keeps its guards.
//
// Thread safety: pure functions.
#include <Eigen/Core>
#include <array>

namespace svmp::cspace::gjk {

struct Simplex {
  std::array<Eigen::Vector3d, 4> p;
  int n = 0;
  // Whether w is already a point (to rounding): GJK has stalled, no new support point to add.
  bool has(const Eigen::Vector3d& w) const;
};

// The point of conv(s) closest to the origin; s keeps only the points of the face holding it (all
// four when the origin is inside the tetrahedron, then the point is the origin).
Eigen::Vector3d closestToOrigin(Simplex& s);

// The same by trying every face; the reference the fast path is tested against, and its fallback.
Eigen::Vector3d closestToOriginByFaces(Simplex& s);

}  // namespace svmp::cspace::gjk
