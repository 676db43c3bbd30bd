#include "planners/local_planner.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "planners/planner_registry.hpp"

namespace svmp::planners {

LocalPlannerOptions LocalPlannerOptions::fromParameters(const cspace::ParameterSet& params) {
  LocalPlannerOptions o;
  o.sigma = params.getDouble("sigma", o.sigma, 1e-9, 1e6);
  o.C = params.getDouble("C", o.C, 1e-9, 1e12);
  o.mu = params.getDouble("mu", o.mu, 0, 1e6);
  o.step = params.getDouble("step", o.step, 1e-9, 1e6);
  o.boundary_tolerance = params.getDouble("boundary_tolerance", o.boundary_tolerance, 0, 1e6);
  o.goal_radius = params.getDouble("goal_radius", o.goal_radius, 0, 1e6);
  o.eps = params.getDouble("eps", o.eps, 1e-15, 1);
  const char* fallback = o.labelling == LabellingMethod::kRandom ? "random" : "balanced";
  o.labelling = params.getString("labelling", fallback, {"balanced", "random"}) == "random"
                    ? LabellingMethod::kRandom
                    : LabellingMethod::kBalanced;
  o.sampling.link_resolution = params.getDouble("link_resolution", o.sampling.link_resolution, 1e-6, 1e6);
  o.sampling.obstacle_resolution = params.getDouble("obstacle_resolution", o.sampling.obstacle_resolution, 1e-6, 1e6);
  o.sampling.boundary_resolution = params.getDouble("boundary_resolution", o.sampling.boundary_resolution, 1e-6, 1e6);
  o.sampling.max_samples = static_cast<int>(params.getInt("max_samples", o.sampling.max_samples, 2, 100000));
  // Every step is a waypoint of the path: at most a million (tens of MB).
  o.max_iterations = static_cast<int>(params.getInt("max_iterations", o.max_iterations, 1, 1000000));
  o.stall_iterations = static_cast<int>(params.getInt("stall_iterations", o.stall_iterations, 1, 1000000));
  return o;
}

std::string LocalPlannerOptions::validate() const {
  if (!(sigma > 0) || !(C > 0) || !(mu >= 0) || !(step > 0) || !std::isfinite(sigma) || !std::isfinite(step))
    return "sigma, C and step must be positive and finite, mu >= 0";
  if (max_iterations < 1 || stall_iterations < 1) return "max_iterations and stall_iterations must be >= 1";
  return "";
}

SVMP_REGISTER_PLANNER("local", [](const PlanningContext& context, const cspace::ParameterSet& params) {
  return std::make_unique<LocalPlanner>(context, LocalPlannerOptions::fromParameters(params));
});

LocalPlanner::LocalPlanner(const PlanningContext& context, LocalPlannerOptions options)
    : Planner(context), options_(std::move(options)) {
  if (const std::string err = options_.validate(); !err.empty())
    throw std::invalid_argument("local planner: " + err);
}

void LocalPlanner::clear() {
  forgetBuild();
  clearQuery();
}

void LocalPlanner::clearQuery() {
  samples_ = {};
  labelling_ = {};
  labelled_ = {};
  risk_.reset();
}

PlanStatus LocalPlanner::descend(const cspace::Query& query, const Termination& stop, PlanResult& result) const {
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
    if (stop()) {
      result.message = "time limit reached after " + std::to_string(it) + " descent steps";
      return PlanStatus::kTimeout;
    }
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
      Eigen::VectorXd g_next(x.size());
      std::ostringstream where;
      where << (hit != cspace::kFree ? "a descent step ended " + cspace::describeHit(context_.checker.environment(), hit)
                                     : std::string("a descent step crossed an obstacle between two free configurations"))
            << " at [" << q_next.transpose() << "], F = " << decision(next, g_next) << " there (" << f
            << " at the step's start)";
      result.message = where.str();
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

void LocalPlanner::answer(const cspace::Query& query, std::uint64_t seed, const Termination& stop,
                          PlanResult& result) {
  if (const std::string why = RiskFunction::unsupported(context_.space.dim()); !why.empty()) {
    result.status = PlanStatus::kInvalidInput;
    result.message = "local planner: " + why;
    return;
  }
  if ((query.goal - query.start).norm() < 1e-12) {  // no hyperplane is needed to stay put
    result.status = PlanStatus::kSolved;
    result.path = {query.start, query.goal};
    return;
  }
  auto t0 = Clock::now();
  try {  // a robot without closed-form IK: this query cannot be posed to the planner
    samples_ = sampleObstaclesByIk(context_.checker, context_.space, options_.sampling, seed, stop.asFunction());
    if (samples_.stopped) {
      result.status = PlanStatus::kTimeout;
      result.message = "time limit reached while sampling the obstacles";
      return;
    }
    labelling_ = labelByHyperplane(samples_.points, samples_.regions, kBoundaryRegion, query.start, query.goal,
                                   options_.labelling, seed);
  } catch (const std::invalid_argument& e) {
    result.status = PlanStatus::kInvalidInput;
    result.message = e.what();
    return;
  }
  result.times.sampling_ms += msSince(t0);
  if (!labelling_.both_classes) {
    result.status = PlanStatus::kFailed;
    result.message = "local planner: the labelling put every sample in one class";
    return;
  }
  labelled_.points = samples_.points;
  for (int i = 0; i < labelling_.y.size(); ++i) {
    labelled_.labels.push_back(labelling_.y[i] > 0 ? 1 : 2);
    labelled_.boundary.push_back(0);
  }
  if (stop()) {
    result.status = PlanStatus::kTimeout;
    result.message = "time limit reached after sampling";
    return;
  }
  t0 = Clock::now();
  Eigen::VectorXd C(samples_.size());
  for (int i = 0; i < samples_.size(); ++i)
    C[i] = options_.C * (samples_.regions[i] == kBoundaryRegion
                             ? 1.0
                             : context_.checker.environment().byId(samples_.regions[i]).weight);
  svm::SolverOptions solver;
  solver.eps = options_.eps;
  solver.stop = stop.asFunction();
  risk_.emplace(RiskFunction::trainBinary(samples_.points, labelling_.y, C, options_.sigma, solver,
                                          context_.space.metricScale(), true, &workspace_));
  result.support_vectors = risk_->model(0).numSupportVectors();
  result.times.training_ms += msSince(t0);
  if (stop()) {
    result.status = PlanStatus::kTimeout;
    result.message = "time limit reached while training";
    return;
  }
  t0 = Clock::now();
  result.status = descend(query, stop, result);
  result.times.query_ms += msSince(t0);
  // A failed descent keeps its partial path (pictures show where it stopped); nothing else does.
  if (result.status != PlanStatus::kSolved && result.status != PlanStatus::kLocalMinimum &&
      result.status != PlanStatus::kFailed)
    result.path.clear();
}

}  // namespace svmp::planners
