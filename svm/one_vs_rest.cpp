#include "svm/one_vs_rest.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <omp.h>
#include <set>
#include <sstream>
#include <stdexcept>

namespace svmp::svm {

void oneVsRestProblem(const std::vector<int>& labels, int positive_class, double C,
                      const std::map<int, double>& class_weight, Eigen::VectorXd& y,
                      Eigen::VectorXd& sample_C) {
  const Eigen::Index n = static_cast<Eigen::Index>(labels.size());
  y.resize(n);
  sample_C.resize(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    y[i] = labels[i] == positive_class ? 1.0 : -1.0;
    const auto w = class_weight.find(labels[i]);
    sample_C[i] = C * (w == class_weight.end() ? 1.0 : w->second);
  }
}

OneVsRestModel trainOneVsRest(const Eigen::MatrixXd& X, const std::vector<int>& labels,
                              const Kernel& kernel, double C,
                              const std::map<int, double>& class_weight, const SolverOptions& opt,
                              int threads) {
  std::ostringstream msg;
  if (static_cast<Eigen::Index>(labels.size()) != X.cols()) {
    msg << "trainOneVsRest: " << labels.size() << " labels for " << X.cols() << " samples";
    throw std::invalid_argument(msg.str());
  }
  if (!(C > 0.0) || !std::isfinite(C)) {
    msg << "trainOneVsRest: C must be positive and finite, got " << C;
    throw std::invalid_argument(msg.str());
  }
  for (const auto& [label, w] : class_weight) {
    if (!(w > 0.0) || !std::isfinite(w)) {
      msg << "trainOneVsRest: weight of class " << label << " must be positive, got " << w;
      throw std::invalid_argument(msg.str());
    }
  }
  if (threads < 1) throw std::invalid_argument("trainOneVsRest: threads must be >= 1");
  const std::set<int> distinct(labels.begin(), labels.end());
  if (distinct.size() < 2) {
    msg << "trainOneVsRest: need at least 2 classes, got " << distinct.size();
    throw std::invalid_argument(msg.str());
  }

  OneVsRestModel out;
  out.classes.assign(distinct.begin(), distinct.end());
  const int k = static_cast<int>(out.classes.size());
  out.models.resize(k);
  out.solutions.resize(k);
  const int workers = std::min(threads, k);
  SolverOptions per_problem = opt;
  std::vector<std::exception_ptr> errors(k);
  // One workspace per thread: a thread's next class reuses its column cache's memory.
  std::vector<SolverWorkspace> workspaces(workers);
#pragma omp parallel for num_threads(workers) schedule(dynamic, 1)
  for (int c = 0; c < k; ++c) {
    try {
      Eigen::VectorXd y, sample_C;
      oneVsRestProblem(labels, out.classes[c], C, class_weight, y, sample_C);
      out.solutions[c] = solveBinary(X, y, sample_C, kernel, per_problem, nullptr,
                                     &workspaces[omp_get_thread_num()]);
      out.solutions[c].workspace_solve = 0;  // the workspaces end here
      out.models[c] = BinaryModel::fromSolution(X, y, out.solutions[c], kernel);
    } catch (...) {
      errors[c] = std::current_exception();
    }
  }
  for (auto& e : errors)
    if (e) std::rethrow_exception(e);
  return out;
}

}  // namespace svmp::svm
