#include "planners/geometry.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace svmp::planners {

std::vector<Segment2> zeroLevelSet(const std::function<double(const Point2&)>& f, const Point2& lo,
                                   const Point2& hi, int grid) {
  const int n = grid + 1;
  const Point2 cell = (hi - lo) / grid;
  std::vector<double> value(static_cast<size_t>(n) * n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) value[j * n + i] = f(lo + Point2(i * cell.x(), j * cell.y()));
  std::vector<Segment2> segments;
  for (int j = 0; j < grid; ++j)
    for (int i = 0; i < grid; ++i) {
      // Corners counter-clockwise from bottom-left; edge e joins corner e and corner e + 1.
      const int ci[4] = {i, i + 1, i + 1, i}, cj[4] = {j, j, j + 1, j + 1};
      double v[4];
      Point2 crossing[4];
      int crossed[4], count = 0;
      for (int c = 0; c < 4; ++c) v[c] = value[cj[c] * n + ci[c]];
      for (int e = 0; e < 4; ++e) {
        const int a = e, b = (e + 1) % 4;
        if ((v[a] > 0) == (v[b] > 0)) continue;
        const double t = v[a] / (v[a] - v[b]);
        const Point2 pa = lo + Point2(ci[a] * cell.x(), cj[a] * cell.y());
        const Point2 pb = lo + Point2(ci[b] * cell.x(), cj[b] * cell.y());
        crossing[e] = pa + t * (pb - pa);
        crossed[count++] = e;
      }
      if (count == 2) {
        segments.emplace_back(crossing[crossed[0]], crossing[crossed[1]]);
      } else if (count == 4) {  // saddle: the centre's sign decides which corners are cut off
        if ((v[0] + v[1] + v[2] + v[3] > 0) == (v[0] > 0)) {
          segments.emplace_back(crossing[0], crossing[1]);
          segments.emplace_back(crossing[2], crossing[3]);
        } else {
          segments.emplace_back(crossing[3], crossing[0]);
          segments.emplace_back(crossing[1], crossing[2]);
        }
      }
    }
  return segments;
}

Polygon convexHull(Polygon points) {
  std::sort(points.begin(), points.end(), [](const Point2& a, const Point2& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  if (points.size() < 3) return points;
  const auto cross = [](const Point2& o, const Point2& a, const Point2& b) {
    return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
  };
  Polygon hull(2 * points.size());
  size_t k = 0;
  for (size_t i = 0; i < points.size(); ++i) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
    hull[k++] = points[i];
  }
  for (size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && cross(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
    hull[k++] = points[i];
  }
  hull.resize(k - 1);
  return hull;
}

Polygon projectedOutline(const robots::Shape& shape, const Eigen::Isometry3d& pose, int arc_points) {
  Polygon points;
  const Eigen::Vector3d& d = shape.dims;
  const double length = shape.kind == robots::ShapeKind::kSphere ? 0 : d.y();
  const auto circleAround = [&](const Point2& centre, double r) {
    for (int a = 0; a < arc_points; ++a) {
      const double t = 2 * std::numbers::pi * a / arc_points;
      points.push_back(centre + r * Point2(std::cos(t), std::sin(t)));
    }
  };
  switch (shape.kind) {
    case robots::ShapeKind::kBox:
      for (int c = 0; c < 8; ++c)
        points.push_back((pose * Eigen::Vector3d((c & 1 ? 0.5 : -0.5) * d.x(), (c & 2 ? 0.5 : -0.5) * d.y(),
                                                 (c & 4 ? 0.5 : -0.5) * d.z()))
                             .head<2>());
      break;
    case robots::ShapeKind::kCylinder:
      for (int a = 0; a < arc_points; ++a) {
        const double t = 2 * std::numbers::pi * a / arc_points;
        for (double z : {-0.5 * length, 0.5 * length})
          points.push_back((pose * Eigen::Vector3d(d.x() * std::cos(t), d.x() * std::sin(t), z)).head<2>());
      }
      break;
    case robots::ShapeKind::kSphere:  // a capsule of length 0
    case robots::ShapeKind::kCapsule:
      for (double z : {-0.5 * length, 0.5 * length}) circleAround((pose * Eigen::Vector3d(0, 0, z)).head<2>(), d.x());
      break;
  }
  return convexHull(std::move(points));
}

std::vector<Polygon> robotOutlines(const robots::Robot& robot, const Eigen::VectorXd& q, int arc_points) {
  robots::Poses poses;
  robot.linkPoses(q, poses);
  std::vector<Polygon> outlines;
  for (int link = 0; link < robot.numLinks(); ++link)
    for (const robots::Shape& shape : robot.linkShapes(link))
      outlines.push_back(projectedOutline(shape, poses[link] * shape.pose, arc_points));
  return outlines;
}

}  // namespace svmp::planners
