#pragma once
// IK-based obstacle sampling of the local SVM-based planner, thesis ch. 2.2.1 (eqs. 2.22-2.23): points
// along each link and on each obstacle's surface at set resolutions; for every pair <link point,
// obstacle point> the configurations that put that link point on that obstacle point (closed-form IK
// of robots/, free joints sampled); plus samples of the configuration-space boundary (joint limits).
// Supports planar arms (robots::PlanarArm) and the CRS-F3 elbow structure (robots::DhArm, first three
// joints). Surface points of a planar robot's obstacles lie on their cross-section with z = 0.
#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "cspace/validity_checker.hpp"
#include "cspace/configuration_space.hpp"

namespace svmp::planners {

// Label of configuration-space boundary samples (they belong to no obstacle).
inline constexpr int kBoundaryRegion = 0;

struct IkSamplingOptions {
  double link_resolution = 0.05;      // spacing of link points (m)
  double obstacle_resolution = 0.05;  // spacing of obstacle surface points (m)
  double boundary_resolution = 0.2;   // spacing of joint-limit samples (rad)
  int free_joint_draws = 1;           // random draws of the free joints per pair
  int max_samples = 4000;             // uniform thinning beyond this (keeps SVM training bounded)
  // Where the resolutions would give more <link point, obstacle point> pairs than this (a bound
  // over the obstacles' bounding spheres; an arm and obstacles hundreds of times larger than the
  // resolutions), both are coarsened by one factor until they do not: about the samples of the
  // robot at the scale the resolutions were meant for, instead of IK solves that grow with the
  // scale squared or cubed. Every file in bench/ stays below it (at most 3.2 million).
  static constexpr double kMaxPairs = 5e6;
  std::string validate() const;
  bool operator==(const IkSamplingOptions&) const = default;
};

struct IkSamples {
  Eigen::MatrixXd points;    // dof x n
  std::vector<int> regions;  // obstacle id, or kBoundaryRegion for joint-limit samples
  bool stopped = false;      // `stop` fired: no samples
  int size() const { return static_cast<int>(regions.size()); }
};

// Throws std::invalid_argument when the robot has no closed-form IK here (point robots, the Panda).
// `stop`, when set, is polled at every obstacle point.
IkSamples sampleObstaclesByIk(const cspace::ValidityChecker& checker,
                              const cspace::ConfigurationSpace& space,
                              const IkSamplingOptions& options, std::uint64_t seed,
                              const std::function<bool()>& stop = {});

// Points on the surface of a shape (world frame) at about `resolution` spacing; for planar robots
// (`planar`), on the outline of its cross-section with the plane z = 0.
std::vector<Eigen::Vector3d> surfacePoints(const robots::Shape& shape, double resolution, bool planar);

}  // namespace svmp::planners
