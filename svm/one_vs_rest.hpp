// One-versus-rest training: one binary C-SVC per class (class k against all other samples), as
// SVMP builds one risk function per obstacle class (thesis ch. 3 and 4.1.2, per-class C).
//
// The problems share the samples and the kernel; only labels and C differ. Where the classes
// interleave (the arms: each problem needs most of the kernel matrix), the problems after the first
// share their kernel columns, computed once (svm/shared_columns.hpp), and solve without shrinking so
// as to read them in place: shrinking's permutation would need every column gathered into each
// solve's cache, which cost as much as computing it. The first problem's solve tells whether that
// pays (shareColumns in one_vs_rest.cpp): on panda_shelf 8 problems of 1,300 samples each computed
// about 1,000 columns, and training fell from 28 to 17 ms; where classes are apart (a point robot in
// a tunnel: each problem needs 5% of the matrix, active sets a fifth of the samples) the solves keep
// a cache each, with shrinking, and where the first problem kept few support vectors (under a
// quarter of the samples: forest_200's colour models keep a tenth) they shrink from the start
// (SolverOptions::early_shrinking). Classes train in parallel (OpenMP, `threads`), the first alone;
// each thread has its own column cache of SolverOptions::cache_mb (memory: threads x cache_mb,
// plus the shared columns, at most cache_mb).
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
  long long shared_columns = 0;         // kernel columns computed once for all problems (0: not shared)
  bool early_shrinking = false;         // the problems after the first shrank from the start
};

// C_i = C * class_weight[labels[i]] (1 when the label is absent). Needs >= 2 classes.
// Throws std::invalid_argument on bad input.
OneVsRestModel trainOneVsRest(const Eigen::MatrixXd& X, const std::vector<int>& labels,
                              const Kernel& kernel, double C,
                              const std::map<int, double>& class_weight, const SolverOptions& opt,
                              int threads);

// The distinct labels, ascending, after checking the arguments both trainings share (throws
// std::invalid_argument naming `who`).
std::vector<int> oneVsRestClasses(const Eigen::MatrixXd& X, const std::vector<int>& labels, double C,
                                  const std::map<int, double>& class_weight, int threads, const char* who);

// Binary labels (+1 for `positive_class`, -1 otherwise) and per-sample C of one OvR problem.
void oneVsRestProblem(const std::vector<int>& labels, int positive_class, double C,
                      const std::map<int, double>& class_weight, Eigen::VectorXd& y,
                      Eigen::VectorXd& sample_C);

}  // namespace svmp::svm
