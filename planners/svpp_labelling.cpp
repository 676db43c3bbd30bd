#include "planners/svpp_labelling.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace svmp::planners {
namespace {

// Extent of an obstacle in frame coordinates: along, side and lateral ranges of its vertices.
struct Extent {
  double t_lo, t_hi, side_lo, side_hi, l_lo, l_hi;
};

Extent extentOf(const SvppObstacle& o, const NominalFrame& frame) {
  Extent e{1e300, -1e300, 1e300, -1e300, 1e300, -1e300};
  for (Eigen::Index v = 0; v < o.vertices.cols(); ++v) {
    const Eigen::VectorXd p = o.vertices.col(v);
    const double t = frame.at(p), s = frame.side(p), l = frame.lateral(p);
    e.t_lo = std::min(e.t_lo, t), e.t_hi = std::max(e.t_hi, t);
    e.side_lo = std::min(e.side_lo, s), e.side_hi = std::max(e.side_hi, s);
    e.l_lo = std::min(e.l_lo, l), e.l_hi = std::max(e.l_hi, l);
  }
  return e;
}

// Evenly spaced values from lo to hi with spacing at most `spacing` (both ends included).
std::vector<double> spaced(double lo, double hi, double spacing) {
  const int n = std::max(1, static_cast<int>(std::ceil((hi - lo) / spacing - 1e-9)));
  std::vector<double> v;
  for (int i = 0; i <= n; ++i) v.push_back(lo + (hi - lo) * i / n);
  return v;
}

Eigen::VectorXd anyPerpendicular(const Eigen::Vector3d& u) {
  const Eigen::Vector3d trial =
      std::abs(u.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  return (trial - trial.dot(u) * u).normalized();
}

}  // namespace

Eigen::VectorXd NominalFrame::point(double t, double side_offset, double lateral_offset) const {
  Eigen::VectorXd p = origin + t * along + side_offset * normal;
  if (across.size()) p += lateral_offset * across;
  return p;
}

NominalFrame nominalLine(const Eigen::VectorXd& start, const Eigen::VectorXd& goal) {
  if (start.size() != 2 || goal.size() != 2)
    throw std::invalid_argument("svpp: the nominal line is 2-D");
  NominalFrame f;
  f.origin = start;
  f.length = (goal - start).norm();
  if (!(f.length > 1e-12)) throw std::invalid_argument("svpp: start and goal coincide");
  f.along = (goal - start) / f.length;
  f.normal = Eigen::Vector2d(f.along.y(), -f.along.x());  // right of the direction of travel
  return f;
}

NominalFrame nominalPlane(const Eigen::VectorXd& start, const Eigen::VectorXd& goal,
                          const Eigen::MatrixXd& vertices) {
  if (start.size() != 3 || goal.size() != 3)
    throw std::invalid_argument("svpp: the nominal plane is 3-D");
  NominalFrame f;
  f.origin = start;
  f.length = (goal - start).norm();
  if (!(f.length > 1e-12)) throw std::invalid_argument("svpp: start and goal coincide");
  const Eigen::Vector3d u = (goal - start) / f.length;
  f.along = u;
  Eigen::Vector3d normal = anyPerpendicular(u);
  if (vertices.cols() >= 2) {
    // Covariance of the vertices with their component along the line removed.
    const Eigen::Matrix3d projector = Eigen::Matrix3d::Identity() - u * u.transpose();
    const Eigen::Matrix3Xd p = projector * vertices;
    const Eigen::Matrix3Xd centred = p.colwise() - p.rowwise().mean();
    const Eigen::Matrix3d covariance =
        centred * centred.transpose() / static_cast<double>(vertices.cols());
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(
        covariance);  // ascending eigenvalues
    if (eigen.eigenvalues()[2] > 1e-12)
      normal = (projector * eigen.eigenvectors().col(2)).normalized();
  }
  // A sign fixed by the data, not by the eigen solver: the normal's largest coordinate is positive.
  Eigen::Index largest = 0;
  normal.cwiseAbs().maxCoeff(&largest);
  if (normal[largest] < 0) normal = -normal;
  f.normal = normal;
  f.across = normal.cross(u);
  return f;
}

void TrainingSet::add(const Eigen::VectorXd& x, double label, SampleKind k) {
  const Eigen::Index n = y.size();
  if (X.cols() == n) {  // grow geometrically
    X.conservativeResize(x.size(), std::max<Eigen::Index>(16, 2 * n));
    y.conservativeResize(n);
  }
  X.col(n) = x;
  y.conservativeResize(n + 1);
  y[n] = label;
  kind.push_back(k);
}

Pattern initialPattern(const std::vector<SvppObstacle>& obstacles, const NominalFrame& frame) {
  Pattern p;
  for (const SvppObstacle& o : obstacles) p.push_back(frame.side(o.centroid) > 0);
  return p;
}

void addVirtualSamples(const NominalFrame& frame, const SampleLayout& layout, TrainingSet& set) {
  addVirtualSamplesAt(frame, 0.0, layout, set);
  addVirtualSamplesAt(frame, frame.length, layout, set);
}

void addVirtualSamplesAt(const NominalFrame& frame, double t_end, const SampleLayout& layout,
                         TrainingSet& set) {
  const int n = layout.virtual_samples;
  const double d = layout.virtual_distance;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < (frame.dim() == 3 ? n : 1); ++j) {
      const double t = t_end + (i - 0.5 * (n - 1)) * d;
      const double l = frame.dim() == 3 ? (j - 0.5 * (n - 1)) * d : 0.0;
      set.add(frame.point(t, d, l), 1, SampleKind::kVirtual);
      set.add(frame.point(t, -d, l), -1, SampleKind::kVirtual);
    }
}

void addGuideSamples(const NominalFrame& frame, const std::vector<SvppObstacle>& obstacles,
                     const Pattern& pattern, const SampleLayout& layout,
                     const Eigen::VectorXd& lower, const Eigen::VectorXd& upper, TrainingSet& set) {
  const double dg = layout.guide_distance;
  std::vector<Extent> extents;
  for (const SvppObstacle& o : obstacles) extents.push_back(extentOf(o, frame));
  const std::vector<double> ts = spaced(0, frame.length, layout.guide_spacing);
  std::vector<double> ls = {0.0};
  if (frame.dim() == 3) {  // the offset planes inside the space grown by d_g
    double l_lo = 1e300, l_hi = -1e300;
    for (int c = 0; c < 8; ++c) {  // the bounds' corners, written out (GCC 12 misreads Eigen here)
      double l = 0;
      for (int k = 0; k < 3; ++k)
        l += frame.across[k] * ((c >> k & 1 ? upper[k] + dg : lower[k] - dg) - frame.origin[k]);
      l_lo = std::min(l_lo, l), l_hi = std::max(l_hi, l);
    }
    ls = spaced(l_lo, l_hi, layout.guide_spacing);
  }
  for (double t : ts)
    for (double l : ls)
      for (const double sign : {1.0, -1.0}) {
        if (frame.dim() == 3) {
          const Eigen::VectorXd p = frame.point(t, sign * dg, l);
          if (((p - lower).array() < -dg).any() || ((p - upper).array() > dg).any()) continue;
        }
        // How deep an obstacle of the other class reaches into this side, where it covers (t, l).
        double depth = 0;
        for (size_t k = 0; k < obstacles.size(); ++k) {
          const bool other_class = (pattern[k] != 0) != (sign > 0);
          const Extent& e = extents[k];
          if (!other_class || t < e.t_lo - dg || t > e.t_hi + dg) continue;
          if (frame.dim() == 3 && (l < e.l_lo - dg || l > e.l_hi + dg)) continue;
          depth = std::max(depth, sign > 0 ? e.side_hi : -e.side_lo);
        }
        set.add(frame.point(t, sign * (dg + depth), l), sign, SampleKind::kGuide);
      }
}

TrainingSet patternTrainingSet(const NominalFrame& frame,
                               const std::vector<SvppObstacle>& obstacles, const Pattern& pattern,
                               const SampleLayout& layout, const Eigen::VectorXd& lower,
                               const Eigen::VectorXd& upper) {
  TrainingSet set;
  for (size_t k = 0; k < obstacles.size(); ++k)
    for (Eigen::Index i = 0; i < obstacles[k].samples.cols(); ++i)
      set.add(obstacles[k].samples.col(i), pattern[k] ? 1 : -1, SampleKind::kObstacle);
  addVirtualSamples(frame, layout, set);
  addGuideSamples(frame, obstacles, pattern, layout, lower, upper, set);
  set.shrinkToFit();
  return set;
}

}  // namespace svmp::planners
