#include "planners/risk_function.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "svm/local_one_vs_rest.hpp"
#include "svm/one_vs_rest.hpp"

namespace svmp::planners {
namespace {

constexpr int kMaxDimensions = 32;  // joints, or control points of the FK kernel

// Stack storage for per-call scaled coordinates and gradients: no allocation in the hot loop.
using SmallVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 32, 1>;
using FeatureVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 96, 1>;

}  // namespace

const char* descentStatusName(DescentStatus status) {
  switch (status) {
    case DescentStatus::kOnBoundary: return "on_boundary";
    case DescentStatus::kLocalMinimum: return "local_minimum";
    case DescentStatus::kIterationLimit: return "iteration_limit";
  }
  return "?";
}

namespace {

// The features the models of a risk function take: control-point positions, 3 per point.
Eigen::MatrixXd controlPointFeatures(const robots::Robot& robot, const Eigen::MatrixXd& configurations) {
  Eigen::MatrixXd features(3 * robot.numControlPoints(), configurations.cols());
  Eigen::Matrix3Xd points;
  for (Eigen::Index i = 0; i < configurations.cols(); ++i) {
    robot.controlPoints(configurations.col(i), points);
    features.col(i) = Eigen::Map<const Eigen::VectorXd>(points.data(), points.size());
  }
  return features;
}

}  // namespace

std::string RiskFunction::unsupported(int dof, const robots::Robot* fk) {
  if (dof > kMaxDimensions)
    return "the risk function takes at most " + std::to_string(kMaxDimensions) + " joints; the robot has " +
           std::to_string(dof);
  if (fk && fk->numControlPoints() > kMaxDimensions)
    return "the FK kernel takes at most " + std::to_string(kMaxDimensions) + " control points; the robot has " +
           std::to_string(fk->numControlPoints());
  return "";
}

RiskFunction::RiskFunction(std::vector<svm::BinaryModel> models, std::vector<int> classes,
                           Eigen::VectorXd scale, bool truncated, const robots::Robot* fk)
    : models_(std::move(models)), classes_(std::move(classes)), scale_(std::move(scale)), fk_(fk) {
  if (models_.empty() || models_.size() != classes_.size())
    throw std::invalid_argument("risk function: need one model per class");
  if (const std::string why = unsupported(static_cast<int>(scale_.size()), fk_); !why.empty())
    throw std::invalid_argument("risk function: " + why);
  const long features = fk_ ? 3L * fk_->numControlPoints() : scale_.size();
  for (const auto& m : models_)
    if (m.dim() != features)
      throw std::invalid_argument("risk function: model dimension differs from the features'");
  if (truncated && models_.front().kernel().isPlainRbf())
    for (const auto& m : models_) truncated_.emplace_back(m);
}

RiskFunction RiskFunction::trainOneVsRest(const Eigen::MatrixXd& configurations, const std::vector<int>& labels,
                                          double sigma, double C, const std::map<int, double>& class_weight,
                                          const svm::SolverOptions& solver, const Eigen::VectorXd& scale,
                                          bool truncated, int threads, const robots::Robot* fk,
                                          OvrTraining training,
                                          const std::vector<std::vector<int>>* neighbourhoods) {
  const svm::Kernel rbf = svm::Kernel::rbfFromSigma(sigma);
  const Eigen::MatrixXd features =
      fk ? controlPointFeatures(*fk, configurations) : Eigen::MatrixXd(scale.asDiagonal() * configurations);
  if (fk || training == OvrTraining::kFull) {
    svm::OneVsRestModel ovr = svm::trainOneVsRest(features, labels, fk ? svm::Kernel::blockSum(rbf, 3) : rbf, C,
                                                  class_weight, solver, threads);
    return RiskFunction(std::move(ovr.models), std::move(ovr.classes), scale, truncated, fk);
  }
  const std::vector<int> classes = svm::oneVsRestClasses(features, labels, C, class_weight, threads, "trainOneVsRest");
  const bool forced = training == OvrTraining::kNeighbourhood || neighbourhoods;
  std::vector<std::vector<int>> computed;
  if (!neighbourhoods)
    computed = svm::classNeighbourhoods(features, labels, classes, rbf,
                                        forced ? std::numeric_limits<double>::infinity() : svm::kNeighbourhoodShareLimit);
  const auto& hoods = neighbourhoods ? *neighbourhoods : computed;
  const bool local = forced || !hoods.empty();
  svm::OneVsRestModel ovr = local ? svm::trainOneVsRestLocal(features, labels, rbf, C, class_weight, solver, threads, &hoods)
                                  : svm::trainOneVsRest(features, labels, rbf, C, class_weight, solver, threads);
  return RiskFunction(std::move(ovr.models), std::move(ovr.classes), scale, truncated, fk);
}

RiskFunction RiskFunction::trainBinary(const Eigen::MatrixXd& configurations, const Eigen::VectorXd& y,
                                       const Eigen::VectorXd& C, double sigma, const svm::SolverOptions& solver,
                                       const Eigen::VectorXd& scale, bool truncated,
                                       svm::SolverWorkspace* workspace) {
  const Eigen::MatrixXd scaled = scale.asDiagonal() * configurations;
  const svm::Kernel kernel = svm::Kernel::rbfFromSigma(sigma);
  const svm::SolverResult solution = svm::solveBinary(scaled, y, C, kernel, solver, nullptr, workspace);
  return RiskFunction({svm::BinaryModel::fromSolution(scaled, y, solution, kernel)}, {1}, scale, truncated);
}

int RiskFunction::classIndex(int label) const {
  auto it = std::find(classes_.begin(), classes_.end(), label);
  return it == classes_.end() ? -1 : static_cast<int>(it - classes_.begin());
}

double RiskFunction::evaluateScaled(int k, const double* x, double* grad_x, bool exact) const {
  if (!fk_) {
    if (!truncated_.empty() && !exact)
      return grad_x ? truncated_[k].decisionAndGradient(x, grad_x) : truncated_[k].decision(x);
    // The exact sum through the evaluator's vectorised leaves; above 16 dimensions its radius search
    // is scalar, no faster than the model's own sum.
    if (!truncated_.empty() && models_[k].dim() <= 16)
      return grad_x ? truncated_[k].exactDecisionAndGradient(x, grad_x) : truncated_[k].exactDecision(x);
    return grad_x ? models_[k].decisionAndGradient(x, grad_x) : models_[k].decision(x);
  }
  const int n = static_cast<int>(scale_.size());
  const Eigen::Map<const Eigen::VectorXd> xs(x, n);
  Eigen::VectorXd q = xs.cwiseQuotient(scale_);
  thread_local Eigen::Matrix3Xd points, moved;
  fk_->controlPoints(q, points);
  const Eigen::Map<const Eigen::VectorXd> phi(points.data(), points.size());
  if (!grad_x) return models_[k].decision(phi.data());
  FeatureVector g(phi.size());
  const double f = models_[k].decisionAndGradient(phi.data(), g.data());
  // dF/dx_j = g . dphi/dq_j / scale_j, dphi/dq_j by a forward difference (FK is smooth).
  constexpr double h = 1e-6;
  for (int j = 0; j < n; ++j) {
    const double qj = q[j];
    q[j] += h;
    fk_->controlPoints(q, moved);
    q[j] = qj;
    const Eigen::Map<const Eigen::VectorXd> phi_j(moved.data(), moved.size());
    grad_x[j] = g.dot(phi_j - phi) / h / scale_[j];
  }
  return f;
}

double RiskFunction::decision(int k, const Eigen::Ref<const Eigen::VectorXd>& q) const {
  const SmallVector x = q.cwiseProduct(scale_);
  return evaluateScaled(k, x.data(), nullptr);
}

double RiskFunction::decisionAndGradient(int k, const Eigen::Ref<const Eigen::VectorXd>& q,
                                         Eigen::Ref<Eigen::VectorXd> grad) const {
  const SmallVector x = q.cwiseProduct(scale_);
  SmallVector gx(x.size());
  const double f = evaluateScaled(k, x.data(), gx.data());
  grad = gx.cwiseProduct(scale_);  // chain rule: dF/dq = dF/dx .* sqrt(w)
  return f;
}

DescentResult RiskFunction::descend(int k, const Eigen::Ref<const Eigen::VectorXd>& q0,
                                    const cspace::ConfigurationSpace& space,
                                    const DescentOptions& options) const {
  const int n = static_cast<int>(scale_.size());
  // Work in scaled coordinates x, where the weighted metric is Euclidean.
  const SmallVector lower = space.lower().cwiseProduct(scale_), upper = space.upper().cwiseProduct(scale_);
  SmallVector x = q0.cwiseProduct(scale_), g(n), trial(n), trial_g(n);
  DescentResult result;
  // The truncated F jumps by up to |coef_i| exp(-5) where a support vector leaves the radius, which can
  // stall the descent just short of F = 0; the exact F, smooth, finishes it in a few Newton steps.
  const bool polish = !truncated_.empty();
  int limit = options.max_iterations;
  auto evaluate = [&](const double* at, double* grad, bool exact) { return evaluateScaled(k, at, grad, exact); };
  for (bool exact : {false, true}) {
    // Polish only where the residual is within the truncation error: elsewhere (far from every
    // support vector, F = bias) the exact F is flat too.
    if (exact && (!polish || result.status == DescentStatus::kOnBoundary ||
                  result.risk > truncated_[k].truncationBound()))
      break;
    double f = evaluate(x.data(), g.data(), exact);
    result.status = DescentStatus::kIterationLimit;
    for (int it = 0; it < limit; ++it, ++result.iterations) {
      if (std::abs(f) <= options.tolerance) {
        result.status = DescentStatus::kOnBoundary;
        break;
      }
      const double g2 = g.squaredNorm();
      if (!(g2 > 1e-300)) {
        result.status = DescentStatus::kLocalMinimum;
        break;
      }
      SmallVector step = (-f / g2) * g;
      const double length = step.norm();
      if (length > options.max_step) step *= options.max_step / length;
      bool improved = false;
      for (int h = 0; h <= options.max_halvings; ++h, step *= 0.5) {
        trial = (x + step).cwiseMax(lower).cwiseMin(upper);
        if ((trial - x).norm() < options.min_step) break;
        const double trial_f = evaluate(trial.data(), trial_g.data(), exact);
        if (std::abs(trial_f) < std::abs(f)) {
          x = trial;
          g = trial_g;
          f = trial_f;
          improved = true;
          break;
        }
      }
      if (!improved) {
        result.status = DescentStatus::kLocalMinimum;
        break;
      }
    }
    if (result.status == DescentStatus::kIterationLimit && std::abs(f) <= options.tolerance)
      result.status = DescentStatus::kOnBoundary;
    result.risk = std::abs(f);
    result.exact = exact || truncated_.empty();
    // Newton on the exact F from within the truncation error lands in a few steps or stalls where F
    // is flat; more steps there cost full sums (svpp_3d20_03: 23 per polish, half of them reaching
    // nothing; 5 steps: 7, and its builds 6.8 -> 4.5 ms at the same success on every file).
    limit = std::min(options.max_iterations, 5);
  }
  result.q = x.cwiseQuotient(scale_);
  return result;
}

}  // namespace svmp::planners
