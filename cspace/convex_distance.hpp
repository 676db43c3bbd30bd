#pragma once
// A certified lower bound on the distance between two placed FCL primitives, for certified motion
// validation (cspace/certified_motion_validator.hpp). FCL 0.7's libccd GJK stops on slow progress
// and then overestimates: by millimetres for box-capsule and cylinder pairs, and by up to half the
// distance for thin coplanar boxes (planar arm links against a block: 0.73 reported for 0.48), so
// its value cannot enter a proof. Any unit direction s gives the bound min over x in A - B of x . s
// (a separating plane); this module evaluates it along the directions of a GJK run of its own
// (Gilbert, Johnson, Keerthi 1988, with van den Bergen's lower-bound stop) on the shapes' cores: a
// capsule is its segment and a sphere its centre, grown by their radii, so against a box the run is
// on a polytope and ends exactly (on round shapes GJK only converges). A sphere against a box or a
// cylinder is in closed form. A bug there can only loosen the bound: every value returned is such a plane's
// separation, never a distance taken on trust. Positive means the shapes are disjoint (one inside
// the other included). GJK's simplex step: cspace/gjk_simplex.hpp.
//
// Thread safety: pure functions.
#include <Eigen/Geometry>
#include <limits>
#include <optional>

#include "robots/shape.hpp"

namespace svmp::cspace {

// The point of shape s farthest along u, s placed at `pose` (its world pose; s.pose is ignored).
Eigen::Vector3d supportPoint(const robots::Shape& s, const Eigen::Isometry3d& pose,
                             const Eigen::Vector3d& u);

// min over x in A - B of x . v / |v| (a lower bound on dist(A, B); -inf for v = 0).
double separationAlong(const robots::Shape& a, const Eigen::Isometry3d& pa, const robots::Shape& b,
                       const Eigen::Isometry3d& pb, const Eigen::Vector3d& v);

// The largest separation found: along `hint` (a vector of A - B, e.g. the centres' offset), then
// along a GJK run until it is within `rel_gap` of the GJK upper bound, or after 64
// iterations, or as soon as it reaches `enough` (a caller keeping the least distance over many
// pairs needs no more of a pair already beyond its least). <= the true distance; <= 0 when no
// separating plane was found (touching, overlapping).
double distanceLowerBound(const robots::Shape& a, const Eigen::Isometry3d& pa,
                          const robots::Shape& b, const Eigen::Isometry3d& pb,
                          const Eigen::Vector3d& hint, double rel_gap = 1e-6,
                          double enough = std::numeric_limits<double>::infinity());

// Whether the placed shapes intersect (touching included), when a GJK run on their cores decides it:
// a plane separating the cores by more than the radii proves them apart, a point of the cores'
// difference within the radii of the origin proves them touching (a sphere against a box or a
// cylinder in closed form, two boxes by the separating-axis test). Empty when the run stalls undecided (round shapes
// grazing each other): ask FCL then. The collision checker's narrow phase
// (cspace/collision_checker.cpp).
std::optional<bool> intersects(const robots::Shape& a, const Eigen::Isometry3d& pa, const robots::Shape& b,
                               const Eigen::Isometry3d& pb);

}  // namespace svmp::cspace
