#include "planners/local_planner.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "svm/smo_solver.hpp"

namespace svmp::planners {

LocalPlanner::LocalPlanner(const PlanningContext& context, LocalPlannerOptions options)
    : context_(context), options_(std::move(options)) {
  if (!(options_.sigma > 0) || !(options_.C > 0) || !(options_.mu >= 0) || !(options_.step > 0))
    throw std::invalid_argument("local planner: sigma, C and step must be positive, mu >= 0");
}

void LocalPlanner::clear() {
  samples_ = {};
  labelling_ = {};
  risk_.reset();
}

PlanStatus LocalPlanner::descend(const cspace::Query& query, PlanResult& result) const {
  // Steepest descent of U = mu |x - x_goal| + |F(x)| in scaled coordinates x = sqrt(w) .* q, where
  // the metric is Euclidean. |F| has a kink on the decision boundary: there the steepest direction is
  // -(mu g + t grad F) with the subgradient weight t in [-1, 1] that minimises its length, so the
  // descent follows the boundary (t inside (-1, 1)) or leaves it towards the goal (t = +-1).
  const auto& space = context_.space;
  const Eigen::VectorXd& scale = space.metricScale();
  const Eigen::VectorXd lower = space.lower().cwiseProduct(scale), upper = space.upper().cwiseProduct(scale);
  const Eigen::VectorXd goal = query.goal.cwiseProduct(scale);
  Eigen::VectorXd x = query.start.cwiseProduct(scale), grad(x.size()), q_prev = query.start;
  result.path = {query.start};
  const double reach = options_.goal_radius < 0 ? options_.sigma : options_.goal_radius;
  double best = (x - goal).norm();
  int since_best = 0;
  auto decision = [&](const Eigen::VectorXd& at, Eigen::VectorXd& g) {
    const double f = risk_->decisionAndGradient(0, at.cwiseQuotient(scale), g);
    g = g.cwiseQuotient(scale);  // dF/dx
    return f;
  };
  for (int it = 0; it < options_.max_iterations; ++it) {
    const double to_goal = (x - goal).norm();
    if (to_goal <= reach && to_goal > options_.step && context_.validator.isValid(q_prev, query.goal)) {
      result.path.push_back(query.goal);
      return PlanStatus::kSolved;
    }
    if (to_goal <= options_.step) {
      if (!context_.validator.isValid(q_prev, query.goal)) {
        result.message = "the last step to the goal is blocked";
        return PlanStatus::kFailed;
      }
      result.path.push_back(query.goal);
      return PlanStatus::kSolved;
    }
    const double f = decision(x, grad);
    const Eigen::VectorXd attraction = options_.mu * (x - goal) / to_goal;
    const double g2 = grad.squaredNorm();
    double t = f >= 0 ? 1.0 : -1.0;
    // On the boundary when F = 0 is within one step to first order: otherwise a step across the kink
    // flips the sign of grad |F| and the descent zig-zags across the boundary instead of following it.
    const double on_boundary = std::max(options_.boundary_tolerance, options_.step * std::sqrt(g2));
    if (std::abs(f) <= on_boundary && g2 > 1e-300)
      t = std::clamp(-attraction.dot(grad) / g2, -1.0, 1.0);
    const Eigen::VectorXd direction = -(attraction + t * grad);
    const double norm = direction.norm();
    if (!(norm > 1e-9 * (options_.mu + std::sqrt(g2)))) {
      result.message = "grad U vanished: attraction balanced by the risk";
      return PlanStatus::kLocalMinimum;
    }
    Eigen::VectorXd next = x + (options_.step / norm) * direction;
    if (std::abs(t) < 1) {  // following the boundary: pull back onto F = 0 against its curvature
      Eigen::VectorXd g_next(x.size());
      const double f_next = decision(next, g_next);
      const double gn2 = g_next.squaredNorm();
      if (gn2 > 1e-300) {
        Eigen::VectorXd correction = -(f_next / gn2) * g_next;
        if (correction.norm() > options_.step) correction *= options_.step / correction.norm();
        next += correction;
      }
    }
    next = next.cwiseMax(lower).cwiseMin(upper);
    const Eigen::VectorXd q_next = next.cwiseQuotient(scale);
    if (const int hit = context_.checker.check(q_next);
        hit != cspace::kFree || !context_.validator.isValid(q_prev, q_next)) {
      result.message = "a descent step entered an obstacle (hit " + std::to_string(hit) + ")";
      return PlanStatus::kFailed;
    }
    x = next;
    q_prev = q_next;
    result.path.push_back(q_next);
    const double d = (x - goal).norm();
    if (d < best - 1e-3 * options_.step) {
      best = d;
      since_best = 0;
    } else if (++since_best >= options_.stall_iterations) {
      std::ostringstream where;
      where << "no progress towards the goal for " << since_best << " steps; stuck at ["
            << q_next.transpose() << "], F = " << f;
      result.message = where.str();
      return PlanStatus::kLocalMinimum;
    }
  }
  result.message = "iteration limit";
  return PlanStatus::kLocalMinimum;
}

PlanResult LocalPlanner::solve(const cspace::Query& query, std::uint64_t seed) {
  clear();
  const auto checks0 = context_.checker.collisionChecks();
  const auto calls0 = context_.validator.calls();
  PlanResult result;
  if (checkEndpoints(context_, query, result)) {
    try {
      auto t0 = Clock::now();
      samples_ = sampleObstaclesByIk(context_.checker, context_.space, options_.sampling, seed);
      labelling_ = labelByHyperplane(samples_.points, samples_.regions, kBoundaryRegion, query.start,
                                     query.goal, options_.labelling, seed);
      result.times.sampling_ms = msSince(t0);
      if (!labelling_.both_classes)
        throw std::invalid_argument("local planner: the labelling put every sample in one class");
      t0 = Clock::now();
      Eigen::VectorXd C(samples_.size());
      for (int i = 0; i < samples_.size(); ++i)
        C[i] = options_.C * (samples_.regions[i] == kBoundaryRegion
                                 ? 1.0
                                 : context_.checker.environment().byId(samples_.regions[i]).weight);
      const Eigen::MatrixXd scaled = context_.space.metricScale().asDiagonal() * samples_.points;
      svm::SolverOptions solver;
      solver.eps = options_.eps;
      const svm::Kernel kernel = svm::Kernel::rbfFromSigma(options_.sigma);
      const svm::SolverResult solution = svm::solveBinary(scaled, labelling_.y, C, kernel, solver);
      risk_.emplace(std::vector<svm::BinaryModel>{svm::BinaryModel::fromSolution(scaled, labelling_.y, solution, kernel)},
                    std::vector<int>{1}, context_.space.metricScale());
      result.support_vectors = risk_->model(0).numSupportVectors();
      result.times.training_ms = msSince(t0);
      t0 = Clock::now();
      result.status = descend(query, result);
      result.times.query_ms = msSince(t0);
    } catch (const std::invalid_argument& e) {
      result.status = PlanStatus::kInvalidInput;
      result.message = e.what();
    }
  }
  if (!result.solved() && result.status != PlanStatus::kLocalMinimum &&
      result.status != PlanStatus::kFailed)
    result.path.clear();
  result.collision_checks = context_.checker.collisionChecks() - checks0;
  result.local_planner_calls = context_.validator.calls() - calls0;
  return result;
}

}  // namespace svmp::planners
