#pragma once
// IK-based obstacle sampling of the local SVM-based planner, thesis ch. 2.2.1 (eqs. 2.22-2.23): points
// along each link and on each obstacle's surface at set resolutions; for every pair <link point,
// obstacle point> the configurations that put that link point on that obstacle point (closed-form IK
// of robots/, free joints sampled); plus samples of the configuration-space boundary (joint limits).
// Supports planar arms (robots::PlanarArm) and the CRS-F3 elbow structure (robots::DhArm, first three
// joints). Surface points of a planar robot's obstacles lie on their cross-section with z = 0.
#include <Eigen/Core>
#include <cstdint>
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
  std::string validate() const;
  bool operator==(const IkSamplingOptions&) const = default;
};

struct IkSamples {
  Eigen::MatrixXd points;    // dof x n
  std::vector<int> regions;  // obstacle id, or kBoundaryRegion for joint-limit samples
  int size() const { return static_cast<int>(regions.size()); }
};

// Throws std::invalid_argument when the robot has no closed-form IK here (point robots, the Panda).
IkSamples sampleObstaclesByIk(const cspace::ValidityChecker& checker,
                              const cspace::ConfigurationSpace& space,
                              const IkSamplingOptions& options, std::uint64_t seed);

// Points on the surface of a shape (world frame) at about `resolution` spacing; for planar robots
// (`planar`), on the outline of its cross-section with the plane z = 0.
std::vector<Eigen::Vector3d> surfacePoints(const robots::Shape& shape, double resolution, bool planar);

}  // namespace svmp::planners
