#pragma once
// Pictures of an SVPP query (svmp-plan --svg DIR with planner svpp) in the style of Miura's Figs. 2, 4
// and 6 (IROS 2006):
//   2-D: one panel per obstacle pattern tried, in order: positive (V >= 1), intermediate and negative
//   (V <= -1) regions shaded light, medium and dark from a grid of V; the merged obstacles outlined in
//   their class colour; obstacle samples as squares (positive) and crosses (negative), guide samples
//   joined by thin lines, virtual samples as circles, support vectors ringed; the surface followed
//   (solid when it reached the goal and passed the validator, dashed otherwise); the returned pattern's
//   panel framed in red.
//   3-D: the returned pattern (else the first tried) in three orthographic projections (x-y, x-z, y-z):
//   obstacle outlines by class, support vectors by label, the path.
// Written whole or not at all (bench/experiments/atomic_file.hpp); throws std::runtime_error naming a
// file that cannot be written. Thread safety: pure function.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "planners/svpp_planner.hpp"

namespace svmp::experiments {

// False (nothing written) when the trace holds no pattern.
bool writeSvppSvg(const std::string& file, const std::string& title,
                  const planners::SvppTrace& trace, const Eigen::VectorXd& lower,
                  const Eigen::VectorXd& upper);

}  // namespace svmp::experiments
