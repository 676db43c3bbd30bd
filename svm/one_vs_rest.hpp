// One-versus-rest training: one binary C-SVC per class (class k against all other samples), as
// SVMP builds one risk function per obstacle class (thesis ch. 3 and 4.1.2, per-class C).
//
// The problems share the samples and the kernel; only labels and C differ. What is shared: the
// validated data and one coordinate-major copy per problem built from it. Kernel columns are NOT
// shared across problems: an RBF column costs ~1 ns per entry with the vectorised exponential,
// while a shared cache would need locking and a gather through each solver's own shrinking
// permutation, which costs about as much as recomputing. Classes train in parallel (OpenMP,
// `threads`), each with its own column cache of SolverOptions::cache_mb (memory: threads x
// cache_mb).
#pragma once

#include <Eigen/Core>
#include <map>
#include <vector>

#include "svm/kernel.hpp"
#include "svm/model.hpp"
#include "svm/smo_solver.hpp"

namespace svmp::svm {

struct OneVsRestModel {
  std::vector<int> classes;             // ascending
  std::vector<BinaryModel> models;      // models[k]: classes[k] is +1, every other class -1
  std::vector<SolverResult> solutions;  // alpha in sample order, for warm starts
};

// C_i = C * class_weight[labels[i]] (1 when the label is absent). Needs >= 2 classes.
// Throws std::invalid_argument on bad input.
OneVsRestModel trainOneVsRest(const Eigen::MatrixXd& X, const std::vector<int>& labels,
                              const Kernel& kernel, double C,
                              const std::map<int, double>& class_weight, const SolverOptions& opt,
                              int threads);

// Binary labels (+1 for `positive_class`, -1 otherwise) and per-sample C of one OvR problem.
void oneVsRestProblem(const std::vector<int>& labels, int positive_class, double C,
                      const std::map<int, double>& class_weight, Eigen::VectorXd& y,
                      Eigen::VectorXd& sample_C);

}  // namespace svmp::svm
