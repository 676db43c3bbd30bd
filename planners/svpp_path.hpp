#pragma once
// Path extraction of Miura's SVPP (IROS 2006): following the separating surface V = 0 of a trained SVM
// (eq. 10) from the start until the goal is within one step.
//   2-D (sec. III-B-5, Fig. 3): from the current point, the next point is where V = 0 on the arc of
//   radius d_s spanning theta_s around the current heading (the crossing nearest the heading; crossings
//   located by bisection on the angle); without a crossing, the arc point of smallest |V| if |V| < 1;
//   none such ends the search (the paper's "no safe next point"), as does the step limit.
//   3-D (sec. IV-B-4, Fig. 5): at the current point a plane is fitted to the surface by searching its
//   pitch and roll (about the surface normal at the point; 3 x 3 grids of +-20, +-6.7, +-2.2 deg) for the
//   least sum of distances between plane points on a circle of radius d_s and the surface (to first
//   order |V| / |grad V(point)|); the direction
//   towards the target (the goal: the nominal line's end) is projected on that plane, a step d_s taken
//   along it, and the point moved back onto V = 0 by Newton steps along grad V; |V| >= 1 after that ends
//   the search.
// A point outside the space's bounds ends the search, as does `stop`, and a path that must end longer than
// `max_length` (length so far + straight distance left; the planner passes the best path found so
// far: a longer one cannot win).
// Pure functions of a const model: thread-safe.
#include <Eigen/Core>
#include <functional>
#include <limits>
#include <vector>

#include "svm/model.hpp"

namespace svmp::planners {

struct SurfaceFollowing {
  double step = 0.05;            // d_s
  double search_angle = 2.0944;  // theta_s in radians (120 deg)
  int max_steps = 500;
  double max_length = std::numeric_limits<double>::infinity();
  Eigen::VectorXd lower, upper;  // the space's bounds
  std::function<bool()> stop;    // polled every step when set: the planner's time limit
};

enum class FollowStatus { kReached, kNoSafePoint, kStepLimit, kLeftSpace, kTooLong, kStopped };
const char* followStatusName(FollowStatus status);

struct FollowResult {
  std::vector<Eigen::VectorXd> path;  // start ... (goal when reached)
  FollowStatus status = FollowStatus::kNoSafePoint;
  double length = 0;
  bool reached() const { return status == FollowStatus::kReached; }
};

// `heading`: the initial direction of travel (the nominal line's direction).
FollowResult followSurface2d(const svm::BinaryModel& model, const Eigen::VectorXd& start,
                             const Eigen::VectorXd& goal, const Eigen::VectorXd& heading,
                             const SurfaceFollowing& options);

// `target(p)`: the point to head for from p (the goal for the planner; a point ahead on the given
// path for smoothing); the search ends at `goal`.
FollowResult followSurface3d(const svm::BinaryModel& model, const Eigen::VectorXd& start,
                             const Eigen::VectorXd& goal,
                             const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& target,
                             const SurfaceFollowing& options);

}  // namespace svmp::planners
