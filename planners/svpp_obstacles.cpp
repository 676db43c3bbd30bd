#include "planners/svpp_obstacles.hpp"

#include <Eigen/Geometry>
#include <numeric>
#include <stdexcept>

#include "planners/geometry.hpp"

namespace svmp::planners {
namespace {

// Projections of the vertices on `axis`.
std::pair<double, double> interval(const Eigen::MatrixXd& vertices, const Eigen::VectorXd& axis) {
  const Eigen::VectorXd p = vertices.transpose() * axis;
  return {p.minCoeff(), p.maxCoeff()};
}

bool separatedAlong(const ConvexPart& a, const ConvexPart& b, const Eigen::VectorXd& axis,
                    double tolerance) {
  const auto [a_lo, a_hi] = interval(a.vertices, axis);
  const auto [b_lo, b_hi] = interval(b.vertices, axis);
  return a_hi < b_lo - tolerance || b_hi < a_lo - tolerance;
}

int findRoot(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

// The shape grown by `r` in every direction (exact for spheres, capsules and boxes' faces).
robots::Shape inflated(robots::Shape shape, double r) {
  switch (shape.kind) {
    case robots::ShapeKind::kBox:
      shape.dims.array() += 2 * r;
      break;
    case robots::ShapeKind::kSphere:
    case robots::ShapeKind::kCapsule:
      shape.dims.x() += r;
      break;
    case robots::ShapeKind::kCylinder:
      shape.dims.x() += r, shape.dims.y() += 2 * r;
      break;
  }
  return shape;
}

// Full sides of the shape's bounding box in its own frame (exact for boxes).
Eigen::Vector3d boundingSides(const robots::Shape& shape) {
  const Eigen::Vector3d& d = shape.dims;
  switch (shape.kind) {
    case robots::ShapeKind::kBox:
      return d;
    case robots::ShapeKind::kSphere:
      return Eigen::Vector3d::Constant(2 * d.x());
    case robots::ShapeKind::kCylinder:
      return {2 * d.x(), 2 * d.x(), d.y()};
    case robots::ShapeKind::kCapsule:
      return {2 * d.x(), 2 * d.x(), d.y() + 2 * d.x()};
  }
  return d;
}

void appendColumn(std::vector<Eigen::VectorXd>& points, const Eigen::VectorXd& p) {
  for (const auto& q : points)
    if ((q - p).squaredNorm() < 1e-24) return;  // shared by two touching parts
  points.push_back(p);
}

Eigen::MatrixXd toMatrix(const std::vector<Eigen::VectorXd>& points, int dim) {
  Eigen::MatrixXd m(dim, static_cast<Eigen::Index>(points.size()));
  for (size_t i = 0; i < points.size(); ++i) m.col(static_cast<Eigen::Index>(i)) = points[i];
  return m;
}

}  // namespace

bool ConvexPart::containsStrictly(const Eigen::VectorXd& p, double margin) const {
  return ((normals.transpose() * p - offsets).array() < -margin).all();
}

ConvexPart polygonPart(const Eigen::Matrix2Xd& v, int obstacle_id) {
  ConvexPart part;
  part.obstacle_id = obstacle_id;
  const int n = static_cast<int>(v.cols());
  if (n < 3) throw std::invalid_argument("svpp: a polygon needs three vertices");
  part.vertices = v;
  part.normals.resize(2, n);
  part.offsets.resize(n);
  double area = 0;
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector2d a = v.col(i), b = v.col((i + 1) % n);
    part.edges.emplace_back(i, (i + 1) % n);
    const Eigen::Vector2d normal =
        Eigen::Vector2d(b.y() - a.y(), a.x() - b.x()).normalized();  // outward (ccw)
    part.normals.col(i) = normal;
    part.offsets[i] = normal.dot(a);
    const double cross = a.x() * b.y() - b.x() * a.y();
    area += cross / 2;
    centroid += (a + b) * cross / 6;
  }
  part.measure = area;
  part.centroid = centroid / area;
  return part;
}

ConvexPart boxPart(const Eigen::Vector3d& centre, const Eigen::Matrix3d& axes,
                   const Eigen::Vector3d& sides, int obstacle_id) {
  ConvexPart part;
  part.obstacle_id = obstacle_id;
  part.vertices.resize(3, 8);
  for (int c = 0; c < 8; ++c) {
    Eigen::Vector3d local;
    for (int k = 0; k < 3; ++k) local[k] = (c >> k & 1 ? 0.5 : -0.5) * sides[k];
    part.vertices.col(c) = centre + axes * local;
  }
  for (int c = 0; c < 8; ++c)
    for (int k = 0; k < 3; ++k)
      if (!(c >> k & 1)) part.edges.emplace_back(c, c | 1 << k);
  part.normals.resize(3, 6);
  part.offsets.resize(6);
  for (int k = 0; k < 3; ++k)
    for (int s = 0; s < 2; ++s) {
      const int f = 2 * k + s;
      std::vector<int> face;  // the four corners with bit k = s, in cyclic order
      const int i = (k + 1) % 3, j = (k + 2) % 3;
      for (int corner : {0, 1, 3, 2})
        face.push_back(s << k | (corner & 1) << i | (corner >> 1 & 1) << j);
      part.faces.push_back(face);
      const Eigen::Vector3d normal = (s ? 1.0 : -1.0) * axes.col(k);
      part.normals.col(f) = normal;
      part.offsets[f] = normal.dot(centre) + 0.5 * sides[k];
    }
  part.edge_directions = axes;
  part.measure = sides.prod();
  part.centroid = centre;
  return part;
}

bool partsOverlap(const ConvexPart& a, const ConvexPart& b, double tolerance) {
  for (const ConvexPart* p : {&a, &b})
    for (Eigen::Index k = 0; k < p->normals.cols(); ++k)
      if (separatedAlong(a, b, p->normals.col(k), tolerance)) return false;
  if (a.dim() == 3)
    for (Eigen::Index i = 0; i < a.edge_directions.cols(); ++i)
      for (Eigen::Index j = 0; j < b.edge_directions.cols(); ++j) {
        const Eigen::Vector3d axis = Eigen::Vector3d(a.edge_directions.col(i))
                                         .cross(Eigen::Vector3d(b.edge_directions.col(j)));
        if (axis.norm() > 1e-9 && separatedAlong(a, b, axis.normalized(), tolerance)) return false;
      }
  return true;
}

std::vector<SvppObstacle> mergeObstacles(std::vector<ConvexPart> parts, const std::function<bool()>& stop) {
  const int n = static_cast<int>(parts.size());
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  for (int i = 0; i < n; ++i) {
    if (stop && stop()) return {};
    for (int j = i + 1; j < n; ++j)
      if (findRoot(parent, i) != findRoot(parent, j) && partsOverlap(parts[i], parts[j]))
        parent[findRoot(parent, j)] = findRoot(parent, i);
  }
  std::vector<SvppObstacle> merged;
  std::vector<int> group_of(n, -1);
  for (int i = 0; i < n; ++i) {  // parts come in id order, so groups are ordered by smallest id
    const int root = findRoot(parent, i);
    if (group_of[root] < 0) group_of[root] = static_cast<int>(merged.size()), merged.emplace_back();
    SvppObstacle& o = merged[group_of[root]];
    o.ids.push_back(parts[i].obstacle_id);
    o.parts.push_back(std::move(parts[i]));
  }
  for (SvppObstacle& o : merged) {
    const int dim = o.parts.front().dim();
    double measure = 0;
    o.centroid = Eigen::VectorXd::Zero(dim);
    std::vector<Eigen::VectorXd> samples, vertices;
    for (const ConvexPart& part : o.parts) {
      if (stop && stop()) return {};  // each part is tested against every other of its group
      measure += part.measure;
      o.centroid += part.measure * part.centroid;
      std::vector<Eigen::VectorXd> candidates;
      for (Eigen::Index v = 0; v < part.vertices.cols(); ++v) {
        candidates.push_back(part.vertices.col(v));
        vertices.push_back(part.vertices.col(v));
      }
      for (const auto& [i, j] : part.edges)
        candidates.push_back(0.5 * (part.vertices.col(i) + part.vertices.col(j)));
      for (const auto& face : part.faces) {
        Eigen::VectorXd centre = Eigen::VectorXd::Zero(dim);
        for (int v : face) centre += part.vertices.col(v);
        candidates.push_back(centre / static_cast<double>(face.size()));
      }
      for (const auto& c : candidates) {
        bool inside_other = false;
        for (const ConvexPart& other : o.parts)
          if (&other != &part && other.containsStrictly(c)) inside_other = true;
        if (!inside_other) appendColumn(samples, c);
      }
    }
    o.centroid /= measure;
    o.samples = toMatrix(samples, dim);
    o.vertices = toMatrix(vertices, dim);
  }
  return merged;
}

Eigen::MatrixXd allVertices(const std::vector<SvppObstacle>& obstacles, int dim) {
  Eigen::Index n = 0;
  for (const SvppObstacle& o : obstacles) n += o.vertices.cols();
  Eigen::MatrixXd vertices(dim, n);
  n = 0;
  for (const SvppObstacle& o : obstacles) {
    vertices.middleCols(n, o.vertices.cols()) = o.vertices;
    n += o.vertices.cols();
  }
  return vertices;
}

std::vector<ConvexPart> obstacleParts(const cspace::Environment& environment, int dim,
                                      double inflate) {
  if (dim != 2 && dim != 3)
    throw std::invalid_argument("svpp: obstacles in 2-D or 3-D only, got " + std::to_string(dim));
  std::vector<ConvexPart> parts;
  for (const cspace::Obstacle& o : environment.obstacles()) {
    if (o.is_virtual) continue;
    const robots::Shape shape = inflated(o.shape, inflate);
    if (dim == 2) {
      const Polygon outline = projectedOutline(shape, shape.pose, 16);
      Eigen::Matrix2Xd v(2, static_cast<Eigen::Index>(outline.size()));
      for (size_t i = 0; i < outline.size(); ++i) v.col(static_cast<Eigen::Index>(i)) = outline[i];
      parts.push_back(polygonPart(v, o.id));
    } else {
      parts.push_back(
          boxPart(shape.pose.translation(), shape.pose.linear(), boundingSides(shape), o.id));
    }
  }
  return parts;
}

}  // namespace svmp::planners
