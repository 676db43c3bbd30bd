// One-versus-rest on neighbourhoods, with the bias fixed at -1: each class's problem holds only its
// own samples and the others' within the RBF's truncation radius of them, so its size is that of
// the class and its surroundings, not of all samples. A departure from the thesis' C-SVC (ch. 2.1,
// 3.3), measured in docs/dev-log.md ("One-versus-rest on neighbourhoods").
//
// Why leaving the far samples out is exact: with the kernel truncated where exp(-gamma d^2) <
// exp(-5) (the truncation the risk function evaluates with, thesis ch. 4.3.1) and the bias fixed at
// -1, a negative sample beyond the radius of every positive one has F = -1 + (terms of other
// negatives, all <= 0) <= -1: it meets its margin with alpha = 0. With a free bias it would not. In
// one-versus-rest most samples are such far negatives, and the C-SVC's equality constraint makes each
// a support vector whose small alpha pushes F from the bias (-0.7 to -1 on panda_shelf) down to -1:
// panda_shelf's 8 problems kept ~720 support vectors each, ~550 of them far negatives.
//
// The dual without the equality constraint, min 1/2 a'Qa - p'a, 0 <= a_i <= C_i with
// p_i = 1 - y_i b, is solved by greedy coordinate descent: the coordinate that violates its KKT
// condition most, moved to its one-dimensional minimum clipped to the box (Q_ii = 1), until none
// violates by more than SolverOptions::eps. Kernel columns are computed when a coordinate is first
// chosen. Coordinate descent needs more iterations than SMO's pairs (gap_0.005: 5,000 for 145
// samples), so it pays only where the neighbourhoods are small: `neighbourhoodShare` below.
//
// Thread safety: pure functions; classes train in parallel (OpenMP, `threads`).
#pragma once

#include <Eigen/Core>
#include <limits>
#include <map>
#include <vector>

#include "svm/one_vs_rest.hpp"

namespace svmp::svm {

inline constexpr double kLocalBias = -1.0;  // the fixed bias of every model

// Class classes[k]'s neighbourhood: its samples and every sample within the truncation radius of
// one of them (squared distance < 5 / gamma), in sample order. Plain RBF kernel only. Empty when
// their neighbourhoodShare would exceed max_share (the search stops there: where the neighbourhoods
// cover the space it costs as much as a tenth of the training).
std::vector<std::vector<int>> classNeighbourhoods(const Eigen::MatrixXd& X, const std::vector<int>& labels,
                                                  const std::vector<int>& classes, const Kernel& kernel,
                                                  double max_share = std::numeric_limits<double>::infinity());

// The neighbourhood problems' kernel matrices against the full problems': sum_k m_k^2 / (K n^2).
// Below kNeighbourhoodShareLimit, training on neighbourhoods is the faster (measured on the 33
// bench/scenarios files: 0.02-0.15 where it won, 0.28-0.68 where it lost or tied).
double neighbourhoodShare(const std::vector<std::vector<int>>& neighbourhoods, Eigen::Index n);
inline constexpr double kNeighbourhoodShareLimit = 0.2;

// As trainOneVsRest (same arguments and errors; the kernel must be the plain RBF), each class on its
// neighbourhood (computed here when not given). solutions[k].alpha is in sample order, zero outside
// the neighbourhood; mean_active is the neighbourhood's size; no gradients are kept (no warm start).
OneVsRestModel trainOneVsRestLocal(const Eigen::MatrixXd& X, const std::vector<int>& labels,
                                   const Kernel& kernel, double C,
                                   const std::map<int, double>& class_weight, const SolverOptions& opt,
                                   int threads, const std::vector<std::vector<int>>* neighbourhoods = nullptr);

}  // namespace svmp::svm
