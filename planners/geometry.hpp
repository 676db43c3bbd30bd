#pragma once
// Plane geometry shared by the pictures (bench/experiments/svg_writer) and the planners that follow a
// decision boundary (Miura's SVPP follows V = 0): the zero level set of a function on a grid (marching
// squares, Lorensen and Cline 1987 in 2-D), convex hulls (Andrew's monotone chain) and the outlines of
// FCL primitives projected on the plane z = 0. Pure functions: thread-safe.
#include <Eigen/Geometry>
#include <functional>
#include <utility>
#include <vector>

#include "robots/robot.hpp"
#include "robots/shape.hpp"

namespace svmp::planners {

using Point2 = Eigen::Vector2d;
using Polygon = std::vector<Point2>;
using Segment2 = std::pair<Point2, Point2>;

// Pieces of f = 0 in the rectangle [lo, hi], from f sampled on the nodes of a grid x grid cell grid,
// crossings placed by linear interpolation; saddles resolved by the sign at the cell's centre (mean of
// its corners).
std::vector<Segment2> zeroLevelSet(const std::function<double(const Point2&)>& f, const Point2& lo,
                                   const Point2& hi, int grid);

// Counter-clockwise, collinear points dropped; fewer than three points are returned sorted.
Polygon convexHull(Polygon points);

// Outline of a shape at world pose `pose` projected on z = 0 (convex hull; round parts with
// `arc_points` points per circle).
Polygon projectedOutline(const robots::Shape& shape, const Eigen::Isometry3d& pose, int arc_points);

// Outlines of every link shape of the robot at q.
std::vector<Polygon> robotOutlines(const robots::Robot& robot, const Eigen::VectorXd& q, int arc_points);

}  // namespace svmp::planners
