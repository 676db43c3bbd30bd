#pragma once
// The training set of one obstacle pattern of Miura's SVPP (IROS 2006): the nominal line through start
// and goal (sec. III-B-2) or, in 3-D, the nominal plane through it whose normal is the principal
// component of the obstacle vertices (sec. IV-A); virtual obstacles around start and goal (III-B-2,
// IV-B-1); the initial pattern by the side of each obstacle's centroid (III-B-3, IV-B-2); guide samples
// parallel to the line or plane, shifted where an obstacle of the other class reaches across (III-B-4,
// IV-B-3). "Positive" is the right side of the line looking from start to goal (the paper's
// convention), in 3-D the side the plane normal points to. Readings of details the paper leaves open
// are in docs/svpp.md ("Readings"). Pure functions: thread-safe.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "planners/svpp_obstacles.hpp"

namespace svmp::planners {

// Coordinates relative to the nominal line or plane: `along` the unit direction start -> goal,
// `normal` towards the positive side, `across` (3-D) completing a right-handed frame in the plane.
struct NominalFrame {
  Eigen::VectorXd origin;  // the start
  Eigen::VectorXd along, normal, across;
  double length = 0;  // |goal - start|

  int dim() const { return static_cast<int>(origin.size()); }
  double side(const Eigen::VectorXd& p) const { return normal.dot(p - origin); }
  double at(const Eigen::VectorXd& p) const { return along.dot(p - origin); }
  double lateral(const Eigen::VectorXd& p) const {
    return across.size() ? across.dot(p - origin) : 0.0;
  }
  Eigen::VectorXd point(double t, double side_offset, double lateral_offset = 0) const;
};

// 2-D: the normal is the right-hand normal of the line. Throws std::invalid_argument when start ==
// goal.
NominalFrame nominalLine(const Eigen::VectorXd& start, const Eigen::VectorXd& goal);
// 3-D: the normal is the direction of largest variance of `vertices` (one per column) among the
// directions perpendicular to the line (PCA of the vertices projected along it), so the plane
// contains the line; any perpendicular when the vertices do not vary across it.
NominalFrame nominalPlane(const Eigen::VectorXd& start, const Eigen::VectorXd& goal,
                          const Eigen::MatrixXd& vertices);

enum class SampleKind : std::uint8_t { kObstacle, kVirtual, kGuide };

struct TrainingSet {
  Eigen::MatrixXd X;  // dim x n
  Eigen::VectorXd y;  // +1 positive, -1 negative
  std::vector<SampleKind> kind;
  int size() const { return static_cast<int>(y.size()); }
  // X grows geometrically; shrinkToFit() drops the spare columns before training.
  void add(const Eigen::VectorXd& x, double label, SampleKind k);
  void shrinkToFit() { X.conservativeResize(X.rows(), size()); }
};

// One flag per merged obstacle: true = positive.
using Pattern = std::vector<char>;

struct SampleLayout {
  int virtual_samples = 3;         // N_v per side of each end point
  double virtual_distance = 0.05;  // d_v
  double guide_distance = 0.2;     // d_g
  double guide_spacing = 0.1;      // d_p
};

// The initial pattern: positive where the centroid lies on the positive side.
Pattern initialPattern(const std::vector<SvppObstacle>& obstacles, const NominalFrame& frame);

// Virtual obstacles at start and goal: in 2-D N_v samples each side at distance d_v, spaced d_v
// along the line and centred on the end point; in 3-D an N_v x N_v grid of spacing d_v on each of
// the two planes at +-d_v from the nominal plane, centred on the end point.
void addVirtualSamples(const NominalFrame& frame, const SampleLayout& layout, TrainingSet& set);
// The virtual obstacle of one end point, at position t along the frame's line.
void addVirtualSamplesAt(const NominalFrame& frame, double t_end, const SampleLayout& layout,
                         TrainingSet& set);

// Guide samples at +-d_g from the line (2-D: t = 0, d_p, ..., length) or the plane (3-D: a grid of
// spacing d_p over the part of the offset plane inside [lower, upper] grown by d_g). A guide of one
// class is pushed out to d_g beyond the deepest point by which an obstacle of the other class
// reaches into its side, when the obstacle's extent along the line (and across, in 3-D) grown by
// d_g covers it.
void addGuideSamples(const NominalFrame& frame, const std::vector<SvppObstacle>& obstacles,
                     const Pattern& pattern, const SampleLayout& layout,
                     const Eigen::VectorXd& lower, const Eigen::VectorXd& upper, TrainingSet& set);

// Obstacle samples labelled by the pattern, virtual samples and guide samples.
TrainingSet patternTrainingSet(const NominalFrame& frame,
                               const std::vector<SvppObstacle>& obstacles, const Pattern& pattern,
                               const SampleLayout& layout, const Eigen::VectorXd& lower,
                               const Eigen::VectorXd& upper);

}  // namespace svmp::planners
