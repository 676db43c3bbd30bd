#pragma once
// The obstacles of Miura's Support Vector Path Planning (J. Miura, "Support Vector Path Planning",
// IROS 2006) as SVPP sees them: convex parts in the robot's space (2-D: the obstacle's outline
// projected on z = 0; 3-D: its oriented bounding box, exact for boxes), merged into one obstacle
// when they overlap or touch (sec. III-C: "a set of obstacles that overlap with each other is
// considered to be a single obstacle"), each with its training samples: vertices and edge midpoints
// in 2-D (sec. III-B-3), vertices, edge midpoints and face centres in 3-D (sec. IV-B-2). A vertex
// strictly inside another part of the same merged obstacle is dropped (it carries no boundary
// information). Pure functions on values: thread-safe.
#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

#include "cspace/environment.hpp"

namespace svmp::planners {

// A convex polygon (2-D) or polyhedron (3-D) as vertices, the edges and faces drawn between them,
// and the outward face normals with offsets (n . x <= offset inside) for containment and overlap
// tests.
struct ConvexPart {
  int obstacle_id = 0;                     // the environment obstacle it came from
  Eigen::MatrixXd vertices;                // dim x n
  std::vector<std::pair<int, int>> edges;  // vertex index pairs
  std::vector<std::vector<int>> faces;     // 3-D only: vertex indices of each face
  Eigen::MatrixXd normals;                 // dim x faces (2-D: one per edge)
  Eigen::VectorXd offsets;
  Eigen::MatrixXd edge_directions;  // 3-D: the distinct edge directions (cross products in SAT)
  double measure = 0;               // area (2-D) or volume (3-D)
  Eigen::VectorXd centroid;

  int dim() const { return static_cast<int>(vertices.rows()); }
  // Strictly inside, by more than `margin`.
  bool containsStrictly(const Eigen::VectorXd& p, double margin = 1e-9) const;
};

// Counter-clockwise convex polygon (2 x n) as a part.
ConvexPart polygonPart(const Eigen::Matrix2Xd& ccw_vertices, int obstacle_id = 0);
// A box of full sides `sides`, centre `centre` and orientation `axes` (columns: its local x, y, z).
ConvexPart boxPart(const Eigen::Vector3d& centre, const Eigen::Matrix3d& axes,
                   const Eigen::Vector3d& sides, int obstacle_id = 0);

// True when the parts intersect or touch (gap <= tolerance), by the separating axis theorem.
bool partsOverlap(const ConvexPart& a, const ConvexPart& b, double tolerance = 1e-9);

// One obstacle after merging: its parts, its centroid (measure-weighted), its training samples and
// every vertex (PCA of the nominal plane, extent across the nominal line).
struct SvppObstacle {
  std::vector<int> ids;  // environment ids of the merged obstacles, ascending
  std::vector<ConvexPart> parts;
  Eigen::VectorXd centroid;
  Eigen::MatrixXd samples;   // dim x m
  Eigen::MatrixXd vertices;  // dim x (all vertices of all parts)
};

// Every vertex of every obstacle, one per column (`dim` rows when there is none).
Eigen::MatrixXd allVertices(const std::vector<SvppObstacle>& obstacles, int dim);

// Merges overlapping parts (union-find over partsOverlap) and makes each group's samples. Groups
// are ordered by their smallest environment id. Quadratic in the parts that overlap: `stop`, polled
// once a part, ends it with nothing returned.
std::vector<SvppObstacle> mergeObstacles(std::vector<ConvexPart> parts, const std::function<bool()>& stop = {});

// The real (not virtual) obstacles of `environment` as parts in a `dim`-dimensional space (2 or 3),
// grown by `inflate` (the point robot's radius). Throws std::invalid_argument for another dim.
std::vector<ConvexPart> obstacleParts(const cspace::Environment& environment, int dim,
                                      double inflate);

}  // namespace svmp::planners
