#pragma once
// Path simplification, the same for every planner (svmp-plan --simplify): vertex reduction and
// shortcutting as OMPL's PathSimplifier does them (reduceVertices, shortcutPath; Geraerts and Overmars,
// "Creating high-quality paths for motion planning", IJRR 2007), with every new segment proven free
// by the certifying motion validator, so a simplified path is as trustworthy as the path it came from.
// Also OMPL's smoothness measure (PathGeometric::smoothness) to report what simplification did.
// Every random choice flows from the caller's generator. Thread safety: pure functions.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "cspace/configuration_space.hpp"
#include "cspace/motion_validator.hpp"

namespace svmp::planners {

struct SimplifyOptions {
  int rounds = 3;              // reduce-then-shortcut rounds (OMPL's simplifyMax repeats until no gain)
  int max_empty_steps = 0;     // attempts without improvement before a pass stops; 0: the path's size
  double range_ratio = 0.33;   // vertex reduction joins vertices at most this fraction of the path apart
  std::string validate() const;  // "" when usable
};

struct SimplifyResult {
  std::vector<Eigen::VectorXd> path;
  int segments_proven = 0;   // certifier calls made
};

// `path` must be certified by `certifier` already; the result is too (start and goal kept).
SimplifyResult simplifyPath(const std::vector<Eigen::VectorXd>& path, const cspace::MotionValidator& certifier,
                            const cspace::ConfigurationSpace& space, cspace::Rng& rng,
                            const SimplifyOptions& options = {});

// OMPL's smoothness: sum over interior vertices of (2 (pi - angle) / (a + b))^2, a and b the lengths of
// the segments meeting there (metric of `space`); 0 for a straight path, smaller is smoother.
double smoothness(const std::vector<Eigen::VectorXd>& path, const cspace::ConfigurationSpace& space);

double pathLength(const std::vector<Eigen::VectorXd>& path, const cspace::ConfigurationSpace& space);

// The smallest checker.clearance over the path's vertices and the points every `step` (metric of
// `space`) along its segments: the dense scan's value (up to FCL's own distance error), without
// measuring the points that the last measured one proves no closer than the minimum so far. Clearance
// changes by at most how far the robot's points move (robots::Robot::displacementBound), so a point
// at clearance c keeps the next (c - minimum) / (bound per step) points at or above the minimum.
double minClearance(const std::vector<Eigen::VectorXd>& path, const cspace::ValidityChecker& checker,
                    const cspace::ConfigurationSpace& space, double step);

}  // namespace svmp::planners
