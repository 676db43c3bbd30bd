#pragma once
// SVM smoothing of a given piecewise-linear path, Miura's SVPP sec. V-A ("Given a piecewise linear
// path, classification of obstacles into positive or negative is easily performed ... it takes a
// relatively small cost to calculate a separating surface and generate a smooth path"), for point
// robots in 2-D and 3-D (svmp-plan --simplify svpp):
//   - each merged obstacle is labelled by the side of the path its centroid lies on (2-D: right of the
//     nearest segment is positive; 3-D: the side of the ribbon spanned along the path by the PCA
//     normal of the obstacle vertices, made perpendicular to each segment),
//   - virtual obstacles at start and goal across the first and last segments (as sec. III-B-2), and
//     the space's walls as obstacles (samples on the boundary labelled by their side of the path; not
//     in the paper, whose paths stay clear of the walls),
//   - guide samples every d_p along the path at +-d_g from it (3-D: a strip of 9 across the ribbon),
//     dropped where a bend brings them closer than d_g / 2 to the path, inside an obstacle or beyond
//     a wall,
//   - the RBF SVM of the planner's parameters and the surface followed from start to goal (2-D: the
//     arc search of Fig. 3; 3-D: the plane fit of Fig. 5, heading for the point d_g ahead on the
//     given path),
//   - every segment proven free by the certifier, and its minimum clearance at least the given
//     path's (the smoothing is for margin). When any step fails, the given path is kept.
// Thread safety: a pure function (one workspace per thread); the checker and certifier are used
// through their const methods.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "cspace/motion_validator.hpp"
#include "cspace/validity_checker.hpp"
#include "planners/svpp_planner.hpp"
#include "svm/solver_workspace.hpp"

namespace svmp::planners {

struct SvmSmoothing {
  std::vector<Eigen::VectorXd> path;  // the smoothed path, or the given one when smoothing failed
  bool smoothed = false;
  std::string why;  // when not smoothed
  int support_vectors = 0;
};

// `path` runs from start to goal; `certifier` proves the smoothed path (a
// CertifiedMotionValidator). `workspace`, when given, is kept by the caller between paths: its
// kernel cache's memory serves the next path's SVM instead of being faulted in afresh.
SvmSmoothing smoothPathBySvm(const std::vector<Eigen::VectorXd>& path,
                             const cspace::ValidityChecker& checker,
                             const cspace::MotionValidator& certifier,
                             const cspace::ConfigurationSpace& space, const SvppOptions& options,
                             svm::SolverWorkspace* workspace = nullptr, const std::function<bool()>& stop = {});

}  // namespace svmp::planners
