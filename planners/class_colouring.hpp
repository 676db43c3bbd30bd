#pragma once
// Obstacle classes grouped by colour, so that SVMP's one-versus-rest models stop growing with the
// number of obstacles. SVMP needs a maximum-margin boundary between obstacles that are close, not
// between every pair. Two classes are adjacent when one's samples come within `distance` of the
// other's (in the weighted metric; one radius search per sample through a k-d tree, so no close pair
// is missed and the cost is the number of sample pairs within `distance`, not n^2). A greedy
// colouring (Welsh and Powell 1967: largest degree first, then the smallest colour no neighbour has)
// gives adjacent classes different colours. One model per colour then separates every obstacle from
// all of its neighbours.
// Thread safety: a pure function.
#include <Eigen/Core>
#include <map>
#include <vector>

namespace svmp::planners {

// label -> colour (1, 2, ...) for every label in `labels`. points: one sample per column, scaled by
// `scale` (sqrt of the metric weights) before distances are taken.
std::map<int, int> colourClasses(const Eigen::MatrixXd& points, const std::vector<int>& labels,
                                 const Eigen::VectorXd& scale, double distance);

}  // namespace svmp::planners
