#pragma once
// Labelling of the local planner's obstacle samples by a hyperplane through start and goal, thesis
// eqs. 2.24-2.25: P(q) = <w, q> + b with P(start) = P(goal) = 0; each region (an obstacle, or the
// configuration-space boundary) takes the side where most of its samples lie.
//  - kRandom is the thesis' method: one random w orthogonal to goal - start, every region by majority,
//    the boundary as one region. The thesis reports it often puts every sample in one class in higher
//    dimensions (ch. 2.4); measureRandomFailureRate() measures how often.
//  - kBalanced yields two non-empty classes with each obstacle on a consistent side (one label per
//    obstacle): boundary samples are labelled one by one by their side, so the boundary, which surrounds
//    the free space and hence start and goal, contributes to both classes; among random candidates it
//    keeps the hyperplane whose labelling has both classes, then splits the obstacles into two
//    non-empty groups (when there are two or more and a hyperplane through start and goal can), then
//    has every obstacle's samples most consistently on one side. In 2-D the hyperplane is the line
//    through start and goal, so the candidates differ only in sign. both_classes is false only when no
//    candidate separates anything (every sample on one side of every candidate).
#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace svmp::planners {

enum class LabellingMethod { kRandom, kBalanced };

struct Labelling {
  Eigen::VectorXd w;  // normal, in configuration coordinates
  double b = 0;
  Eigen::VectorXd y;  // +1 / -1 per sample
  bool both_classes = false;
};

// `regions[i]` is sample i's region: an obstacle id, or `boundary_region` for joint-limit samples.
Labelling labelByHyperplane(const Eigen::MatrixXd& samples, const std::vector<int>& regions,
                            int boundary_region, const Eigen::VectorXd& start, const Eigen::VectorXd& goal,
                            LabellingMethod method, std::uint64_t seed, int candidates = 256);

// Fraction of `trials` random hyperplanes (kRandom) that put every sample in one class.
double measureRandomFailureRate(const Eigen::MatrixXd& samples, const std::vector<int>& regions,
                                int boundary_region, const Eigen::VectorXd& start,
                                const Eigen::VectorXd& goal, int trials, std::uint64_t seed);

}  // namespace svmp::planners
