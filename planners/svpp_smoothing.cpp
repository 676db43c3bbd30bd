#include "planners/svpp_smoothing.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "planners/path_simplifier.hpp"
#include "robots/point_robot.hpp"

namespace svmp::planners {
namespace {

struct Nearest {
  int segment = 0;
  double t = 0;    // position on the segment, 0..1
  double arc = 0;  // arc length of the nearest point from the start
  double distance = 1e300;
  Eigen::VectorXd point;
};

// The piecewise-linear path with its cumulative lengths.
class Polyline {
 public:
  explicit Polyline(std::vector<Eigen::VectorXd> points)
      : points_(std::move(points)), cumulative_{0} {
    for (size_t i = 1; i < points_.size(); ++i)
      cumulative_.push_back(cumulative_.back() + (points_[i] - points_[i - 1]).norm());
  }
  int segments() const { return static_cast<int>(points_.size()) - 1; }
  double length() const { return cumulative_.back(); }
  Eigen::VectorXd direction(int i) const { return (points_[i + 1] - points_[i]).normalized(); }

  Nearest nearest(const Eigen::VectorXd& p) const {
    Nearest best;
    for (int i = 0; i < segments(); ++i) {
      const Eigen::VectorXd d = points_[i + 1] - points_[i];
      const double t = std::clamp((p - points_[i]).dot(d) / d.squaredNorm(), 0.0, 1.0);
      const Eigen::VectorXd q = points_[i] + t * d;
      const double distance = (p - q).norm();
      if (distance < best.distance) best = {i, t, cumulative_[i] + t * d.norm(), distance, q};
    }
    return best;
  }

  // The point at arc length s (clamped to the ends) and its segment.
  std::pair<Eigen::VectorXd, int> at(double s) const {
    s = std::clamp(s, 0.0, length());
    int i = static_cast<int>(std::upper_bound(cumulative_.begin(), cumulative_.end(), s) -
                             cumulative_.begin()) -
            1;
    i = std::clamp(i, 0, segments() - 1);
    const double span = cumulative_[i + 1] - cumulative_[i];
    return {
        points_[i] + (span > 0 ? (s - cumulative_[i]) / span : 0.0) * (points_[i + 1] - points_[i]),
        i};
  }

 private:
  std::vector<Eigen::VectorXd> points_;
  std::vector<double> cumulative_;
};

std::vector<Eigen::VectorXd> withoutRepeats(const std::vector<Eigen::VectorXd>& path) {
  std::vector<Eigen::VectorXd> out;
  for (const auto& p : path)
    if (out.empty() || (p - out.back()).norm() > 1e-12) out.push_back(p);
  return out;
}

}  // namespace

SvmSmoothing smoothPathBySvm(const std::vector<Eigen::VectorXd>& given,
                             const cspace::ValidityChecker& checker,
                             const cspace::MotionValidator& certifier,
                             const cspace::ConfigurationSpace& space, const SvppOptions& given_options,
                             svm::SolverWorkspace* workspace, const std::function<bool()>& stop) {
  const SvppOptions options = given_options.resolvedFor(space, checker.environment().numReal());
  SvmSmoothing out;
  out.path = given;
  if (const std::string why = options.validateFor(space); !why.empty()) {
    out.why = "svpp parameters: " + why;
    return out;
  }
  const auto* point = dynamic_cast<const robots::PointRobot*>(&checker.robot());
  if (!point) {
    out.why = "SVM smoothing needs a point robot in 2-D or 3-D";
    return out;
  }
  const Polyline path(withoutRepeats(given));
  if (path.segments() < 1) {
    out.why = "the path has no segment";
    return out;
  }
  const int dim = point->dof();
  const std::vector<SvppObstacle> obstacles =
      mergeObstacles(obstacleParts(checker.environment(), dim, point->radius()), stop);
  if (stop && stop()) {
    out.why = "time limit reached while merging overlapping obstacles";
    return out;
  }
  const Eigen::VectorXd start = given.front(), goal = given.back();

  // The side normal of each segment: 2-D its right normal; 3-D the PCA plane normal made
  // perpendicular.
  Eigen::VectorXd plane_normal;
  if (dim == 3) {
    plane_normal =
        nominalPlane(start, (goal - start).norm() > 1e-12 ? goal : start + path.direction(0),
                     allVertices(obstacles, 3))
            .normal;
  }
  const auto sideNormal = [&](int i) -> Eigen::VectorXd {
    const Eigen::VectorXd d = path.direction(i);
    if (dim == 2) return Eigen::Vector2d(d.y(), -d.x());
    Eigen::Vector3d n = plane_normal - plane_normal.dot(d) * d;
    if (n.norm() < 1e-6) n = Eigen::Vector3d(d).unitOrthogonal();
    return n.normalized();
  };
  const auto frameAt = [&](const Eigen::VectorXd& origin, int segment) {
    NominalFrame f;
    f.origin = origin;
    f.along = path.direction(segment);
    f.normal = sideNormal(segment);
    if (dim == 3) f.across = Eigen::Vector3d(f.normal).cross(Eigen::Vector3d(f.along));
    return f;
  };

  // +1 right of (3-D: on the normal's side of) the path; at an interior vertex across the mean of
  // the two segments' normals.
  const auto sideOf = [&](const Eigen::VectorXd& p) {
    const Nearest n = path.nearest(p);
    Eigen::VectorXd normal = sideNormal(n.segment);
    if (n.t >= 1 && n.segment + 1 < path.segments()) normal += sideNormal(n.segment + 1);
    if (n.t <= 0 && n.segment > 0) normal += sideNormal(n.segment - 1);
    return normal.dot(p - n.point) > 0 ? 1.0 : -1.0;
  };
  const SampleLayout layout = options.layout();
  TrainingSet set;
  for (const SvppObstacle& o : obstacles) {
    const double label = sideOf(o.centroid);
    for (Eigen::Index i = 0; i < o.samples.cols(); ++i)
      set.add(o.samples.col(i), label, SampleKind::kObstacle);
  }
  // The space's walls as obstacles too (a path along a wall would otherwise have its separating
  // surface midway between the path's neighbours, outside the space): samples every d_p on the
  // boundary (every 2 d_p in 3-D), each labelled by its own side of the path.
  const Eigen::VectorXd& lower = space.lower();
  const Eigen::VectorXd& upper = space.upper();
  const double wall_spacing = (dim == 2 ? 1 : 2) * layout.guide_spacing;
  std::vector<int> counts(dim);
  for (int k = 0; k < dim; ++k)
    counts[k] = std::max(1, static_cast<int>(std::ceil((upper[k] - lower[k]) / wall_spacing)));
  for (int k = 0; k < dim; ++k)  // the two walls across axis k
    for (const double wall : {lower[k], upper[k]}) {
      const int a = (k + 1) % dim, b = (k + 2) % dim;
      for (int i = 0; i <= counts[a]; ++i)
        for (int j = 0; j <= (dim == 3 ? counts[b] : 0); ++j) {
          Eigen::VectorXd p(dim);
          p[k] = wall;
          p[a] = lower[a] + (upper[a] - lower[a]) * i / counts[a];
          if (dim == 3) p[b] = lower[b] + (upper[b] - lower[b]) * j / counts[b];
          set.add(p, sideOf(p), SampleKind::kVirtual);
        }
    }
  addVirtualSamplesAt(frameAt(start, 0), 0, layout, set);
  addVirtualSamplesAt(frameAt(goal, path.segments() - 1), 0, layout, set);
  const int strip = dim == 3 ? 4 : 0;  // guides across the ribbon: -4..4 spacings in 3-D
  for (double s = 0; s <= path.length() + 1e-9; s += layout.guide_spacing) {
    const auto [p, segment] = path.at(s);
    const NominalFrame f = frameAt(p, segment);
    for (int l = -strip; l <= strip; ++l)
      for (const double sign : {1.0, -1.0}) {
        const Eigen::VectorXd g =
            f.point(0, sign * layout.guide_distance, l * layout.guide_spacing);
        if (path.nearest(g).distance < 0.5 * layout.guide_distance) continue;  // across a bend
        if ((g.array() < lower.array()).any() || (g.array() > upper.array()).any())
          continue;  // beyond a wall
        bool inside = false;
        for (const SvppObstacle& o : obstacles)
          for (const ConvexPart& part : o.parts) inside = inside || part.containsStrictly(g, 0);
        if (!inside) set.add(g, sign, SampleKind::kGuide);
      }
  }
  set.shrinkToFit();

  const svm::BinaryModel model = trainSvppModel(set, options.gamma, options.C, options.eps, workspace, stop);
  if (stop && stop()) {
    out.why = "time limit reached while training the SVM";
    return out;
  }
  out.support_vectors = model.numSupportVectors();
  cspace::Query query;
  query.start = start;
  query.goal = goal;
  SurfaceFollowing following = options.following(query, space.lower(), space.upper());
  following.stop = stop;
  if (options.max_steps == 0)
    following.max_steps = static_cast<int>(std::min(std::ceil(3 * path.length() / options.step), 1e7));
  const FollowResult follow =
      dim == 2 ? followSurface2d(model, start, goal, path.direction(0), following)
               : followSurface3d(
                     model, start, goal,
                     [&](const Eigen::VectorXd& p) {
                       return path.at(path.nearest(p).arc + layout.guide_distance).first;
                     },
                     following);
  if (!follow.reached()) {
    out.why = std::string("surface following: ") + followStatusName(follow.status);
    return out;
  }
  for (size_t i = 0; i + 1 < follow.path.size(); ++i)
    if (!certifier.isValid(follow.path[i], follow.path[i + 1])) {
      out.why = "segment " + std::to_string(i) + " of the smoothed path is not proven free";
      return out;
    }
  // The smoothing is for margin (sec. V-A): a surface that passes nearer an obstacle than the given
  // path does (a corridor's open ends bend it towards the walls) is no improvement.
  const double step = certifier.resolution() / 4;
  if (const double before = minClearance(given, checker, space, step),
      after = minClearance(follow.path, checker, space, step);
      after < before) {
    out.why = "the smoothed path's clearance " + std::to_string(after) + " is below the given path's " +
              std::to_string(before);
    return out;
  }
  out.path = follow.path;
  out.smoothed = true;
  return out;
}

}  // namespace svmp::planners
