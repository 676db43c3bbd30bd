#pragma once
// The risk function R_k(q) = |F_k(q)| (thesis eqs. 2.26 and 3.1) over one-versus-rest SVM models, its
// gradient, and a descent to the decision boundary F_k = 0 where R_k has its minima (ch. 3.3). Shared by
// SVMP (one model per obstacle class) and the local planner of ch. 2 (one binary model).
//
// The models are trained on scaled coordinates x = sqrt(w) .* q so the RBF kernel measures the weighted
// joint metric of eq. 4.3; this class takes and returns configurations q. With an RBF kernel F is
// evaluated through the exp(-5)-truncated sum (ch. 4.3.1); other kernels use the full sum.
// With a forward-kinematics robot (the FK kernel of Das & Yip 2019, eq. 4, beyond the thesis), the
// models are trained on the workspace positions of the robot's control points instead, with the RBF
// summed over control points; dF/dq is the chain rule through the control points' Jacobian (forward
// differences, one control-point evaluation per joint), and the descent still steps in x.
// Thread safety: const methods may be called concurrently.
#include <Eigen/Core>
#include <map>
#include <string>
#include <variant>
#include <vector>

#include "cspace/configuration_space.hpp"
#include "robots/robot.hpp"
#include "svm/model.hpp"
#include "svm/smo_solver.hpp"
#include "svm/truncated_evaluator.hpp"

namespace svmp::planners {

enum class DescentStatus {
  kOnBoundary,     // |F| <= tolerance: a global minimum of R
  kLocalMinimum,   // no step decreases R (flat or stuck with |F| > tolerance)
  kIterationLimit  // max_iterations reached
};

const char* descentStatusName(DescentStatus status);

struct DescentOptions {
  double tolerance = 1e-3;  // |F| at which the boundary counts as reached
  double max_step = 0.1;    // longest step, in the weighted metric
  double min_step = 1e-9;   // a step shorter than this ends the descent as a local minimum
  int max_iterations = 100;
  int max_halvings = 12;    // backtracking halvings before declaring a local minimum
};

struct DescentResult {
  Eigen::VectorXd q;
  double risk = 0;     // |F_k(q)| from the evaluator that finished the descent
  bool exact = false;  // true when that was the exact sum (polishing after a truncated stall)
  int iterations = 0;
  DescentStatus status = DescentStatus::kIterationLimit;
};

// How one-versus-rest trains: the thesis' C-SVC on every sample (kFull), each class on its
// neighbourhood with a fixed bias (kNeighbourhood, svm/local_one_vs_rest.hpp), or the latter where
// the neighbourhoods are small enough to pay (kAuto: svm::neighbourhoodShare below its limit). The
// FK kernel always trains kFull. Neighbourhoods the caller already has (svm::classNeighbourhoods over
// the same scaled samples and classes) are trained on as they are, unless kFull.
enum class OvrTraining { kFull, kNeighbourhood, kAuto };

class RiskFunction {
 public:
  // Why a risk function cannot be made for `dof` joints (or, with `fk`, that robot's control points):
  // at most 32 of either (the fixed-size buffers of its evaluation); "" when it can. The planners on
  // it report kInvalidInput with this message before any work.
  static std::string unsupported(int dof, const robots::Robot* fk = nullptr);

  // `fk`: null for models on scaled joints; else the robot whose control points the models take.
  RiskFunction(std::vector<svm::BinaryModel> models, std::vector<int> classes, Eigen::VectorXd scale,
               bool truncated = true, const robots::Robot* fk = nullptr);

  // Training on configurations (one per column), scaled here by `scale` = sqrt(w) so the RBF of width
  // sigma measures the weighted metric: one-versus-rest over obstacle labels (SVMP, thesis ch. 3.2;
  // C per class = C * class_weight) and one binary model with per-sample C (the local planner, ch. 2).
  static RiskFunction trainOneVsRest(const Eigen::MatrixXd& configurations, const std::vector<int>& labels,
                                     double sigma, double C, const std::map<int, double>& class_weight,
                                     const svm::SolverOptions& solver, const Eigen::VectorXd& scale,
                                     bool truncated, int threads, const robots::Robot* fk = nullptr,
                                     OvrTraining training = OvrTraining::kFull,
                                     const std::vector<std::vector<int>>* neighbourhoods = nullptr);
  // `workspace`: kept by a caller that trains again and again, so that each solve reuses the last
  // one's cache memory instead of faulting in fresh pages (svm/solver_workspace.hpp).
  static RiskFunction trainBinary(const Eigen::MatrixXd& configurations, const Eigen::VectorXd& y,
                                  const Eigen::VectorXd& C, double sigma, const svm::SolverOptions& solver,
                                  const Eigen::VectorXd& scale, bool truncated,
                                  svm::SolverWorkspace* workspace = nullptr);

  int numClasses() const { return static_cast<int>(models_.size()); }
  const std::vector<int>& classes() const { return classes_; }
  // Index k of a class label, -1 when unknown.
  int classIndex(int label) const;
  const svm::BinaryModel& model(int k) const { return models_[k]; }
  const Eigen::VectorXd& scale() const { return scale_; }

  double decision(int k, const Eigen::Ref<const Eigen::VectorXd>& q) const;
  // F_k(q) and dF_k/dq.
  double decisionAndGradient(int k, const Eigen::Ref<const Eigen::VectorXd>& q,
                             Eigen::Ref<Eigen::VectorXd> grad) const;
  double risk(int k, const Eigen::Ref<const Eigen::VectorXd>& q) const { return std::abs(decision(k, q)); }

  // Descends R_k from q0, staying inside the space's bounds: each step is the Newton step towards
  // F_k = 0 along the gradient (-F g / |g|^2 in the scaled coordinates), cut to max_step and halved
  // until R_k decreases. With truncated evaluation, a descent that stalls short of the boundary is
  // finished on the exact F (at most 20 more steps).
  DescentResult descend(int k, const Eigen::Ref<const Eigen::VectorXd>& q0,
                        const cspace::ConfigurationSpace& space, const DescentOptions& options) const;

 private:
  // F_k at scaled coordinates x (and dF/dx when grad_x is not null); `exact` skips the truncation.
  double evaluateScaled(int k, const double* x, double* grad_x, bool exact = false) const;

  std::vector<svm::BinaryModel> models_;
  std::vector<svm::TruncatedRbfEvaluator> truncated_;  // empty unless RBF and truncation asked for
  std::vector<int> classes_;
  Eigen::VectorXd scale_;
  const robots::Robot* fk_ = nullptr;
};

}  // namespace svmp::planners
