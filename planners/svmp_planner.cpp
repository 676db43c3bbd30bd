#include "planners/svmp_planner.hpp"

#include <limits>
#include <map>
#include <random>

#include "planners/roadmap_builder.hpp"
#include "svm/one_vs_rest.hpp"

namespace svmp::planners {

SvmpPlanner::SvmpPlanner(const PlanningContext& context, SvmpOptions options)
    : context_(context), options_(options) {
  if (!(options_.sigma > 0)) throw std::invalid_argument("svmp: sigma must be positive");
  if (!(options_.C > 0)) throw std::invalid_argument("svmp: C must be positive");
  if (options_.descent.max_step <= 0) options_.descent.max_step = options_.sigma;
  if (options_.duplicate_radius < 0) options_.duplicate_radius = 0.5 * options_.step;
}

void SvmpPlanner::clear() {
  samples_ = {};
  risk_.reset();
  roadmap_.clear();
  nn_.reset();
}

int SvmpPlanner::supportVectors() const {
  if (!risk_) return 0;
  int n = 0;
  for (int k = 0; k < risk_->numClasses(); ++k) n += risk_->model(k).numSupportVectors();
  return n;
}

void SvmpPlanner::sampleObstacle(std::uint64_t seed, PhaseTimes& times) {
  const auto t0 = Clock::now();
  cspace::ObstacleSamplerOptions opt;
  opt.step = options_.step;
  opt.samples_per_tree = options_.samples_per_tree;
  opt.include_self_collision = options_.sample_self_collision;
  // Surfaces located to a quarter of the checking resolution: finer than any passage the motion
  // validator can tell apart, coarse enough to cost a few bisection checks per boundary node.
  opt.refine_tolerance = context_.validator.resolution() / 4;
  samples_ = cspace::sampleObstacles(context_.checker, context_.space, opt, seed, context_.threads);
  times.sampling_ms += msSince(t0);
}

void SvmpPlanner::trainMultiSvm(PhaseTimes& times) {
  const auto t0 = Clock::now();
  const cspace::Environment& env = context_.checker.environment();
  std::map<int, double> weights;
  for (int label : samples_.labels) weights[label] = label > 0 ? env.byId(label).weight : 1.0;
  if (weights.size() < 2) {
    const int only = weights.empty() ? 0 : weights.begin()->first;
    const std::string have = weights.empty() ? "none"
                             : only > 0      ? "only '" + env.byId(only).name + "'"
                                             : "only the self-collision region";
    throw std::invalid_argument(
        "svmp: one-versus-rest needs samples of at least two obstacles, got " + have +
        (samples_.warnings.empty() ? "" : " (" + samples_.warnings.front() + ")"));
  }
  const Eigen::MatrixXd scaled = context_.space.metricScale().asDiagonal() * samples_.points;
  svm::SolverOptions solver;
  solver.eps = options_.eps;
  solver.cache_mb = options_.cache_mb;
  svm::OneVsRestModel ovr = svm::trainOneVsRest(scaled, samples_.labels,
                                                svm::Kernel::rbfFromSigma(options_.sigma), options_.C,
                                                weights, solver, context_.threads);
  risk_.emplace(std::move(ovr.models), std::move(ovr.classes), context_.space.metricScale(),
                options_.truncated);
  times.training_ms += msSince(t0);
}

int SvmpPlanner::addMilestones(const std::vector<Eigen::VectorXd>& starts,
                               const std::vector<int>& classes, bool keep_free_starts) {
  const int n = static_cast<int>(starts.size());
  std::vector<Eigen::VectorXd> ends(n);
  std::vector<int> end_class(n);
#pragma omp parallel for schedule(dynamic, 8) num_threads(context_.threads)
  for (int i = 0; i < n; ++i) {
    int k = classes[i];
    if (k < 0) {  // the nearest decision boundary: the class whose |F_k| is smallest here
      double best = std::numeric_limits<double>::infinity();
      for (int c = 0; c < risk_->numClasses(); ++c) {
        const double r = risk_->risk(c, starts[i]);
        if (r < best) best = r, k = c;
      }
    }
    ends[i] = risk_->descend(k, starts[i], context_.space, options_.descent).q;
    end_class[i] = k;
  }
  // Near-duplicates are dropped before any collision check, in a fixed order (deterministic).
  const Eigen::VectorXd& scale = context_.space.metricScale();
  const double r2 = options_.duplicate_radius * options_.duplicate_radius;
  Eigen::MatrixXd kept(scale.size(), roadmap_.numNodes() + n);
  int count = 0;
  for (const auto& q : roadmap_.nodes()) kept.col(count++) = q.cwiseProduct(scale);
  std::vector<int> fresh;
  for (int i = 0; i < n; ++i) {
    const Eigen::VectorXd x = ends[i].cwiseProduct(scale);
    bool duplicate = false;
    for (int j = 0; j < count && !duplicate; ++j) duplicate = (kept.col(j) - x).squaredNorm() < r2;
    if (duplicate) continue;
    kept.col(count++) = x;
    fresh.push_back(i);
  }
  std::vector<char> valid(fresh.size());
#pragma omp parallel for schedule(dynamic, 8) num_threads(context_.threads)
  for (int f = 0; f < static_cast<int>(fresh.size()); ++f) {
    valid[f] = context_.checker.isValid(ends[fresh[f]]);
    if (valid[f]) continue;
    std::optional<Eigen::VectorXd> centre;
    if (options_.centre_in_passage) centre = centreAlongNormal(end_class[fresh[f]], ends[fresh[f]]);
    if (centre) {
      ends[fresh[f]] = *centre;
      valid[f] = 1;
    } else if (keep_free_starts && context_.checker.isValid(starts[fresh[f]])) {
      ends[fresh[f]] = starts[fresh[f]];
      valid[f] = 1;
    }
  }
  int added = 0;
  for (size_t f = 0; f < fresh.size(); ++f)
    if (valid[f]) roadmap_.addNode(ends[fresh[f]]), ++added;
  return added;
}

void SvmpPlanner::findBoundaryMilestones(PhaseTimes& times) {
  if (!risk_) throw std::invalid_argument("svmp: findBoundaryMilestones before trainMultiSvm");
  const auto t0 = Clock::now();
  std::vector<Eigen::VectorXd> starts;
  std::vector<int> classes;
  for (int i = 0; i < samples_.size(); ++i) {
    if (!samples_.boundary[i]) continue;
    starts.push_back(samples_.points.col(i));
    classes.push_back(risk_->classIndex(samples_.labels[i]));
  }
  addMilestones(starts, classes);
  times.milestones_ms += msSince(t0);
}

std::optional<Eigen::VectorXd> SvmpPlanner::centreAlongNormal(int k, const Eigen::VectorXd& q) const {
  const Eigen::VectorXd& scale = context_.space.metricScale();
  Eigen::VectorXd grad(q.size());
  risk_->decisionAndGradient(k, q, grad);
  Eigen::VectorXd normal = grad.cwiseQuotient(scale);  // dF/dx in scaled coordinates
  if (!(normal.norm() > 0)) return std::nullopt;
  normal.normalize();
  const Eigen::VectorXd direction = normal.cwiseQuotient(scale);  // unit length in the metric
  auto at = [&](double t) {
    Eigen::VectorXd p = q + t * direction;
    context_.space.clamp(p);
    return p;
  };
  auto free = [&](double t) { return context_.checker.isValid(at(t)); };
  const double first = context_.validator.resolution() / 4;
  // Nearest free offset on either side, by doubling.
  double inside = 0, outside = 0;
  bool found = false;
  for (double t = first; t <= options_.sigma && !found; t *= 2)
    for (double signed_t : {t, -t})
      if (free(signed_t)) {
        outside = signed_t;
        inside = t == first ? 0 : signed_t / 2;  // blocked: tested one doubling earlier
        found = true;
        break;
      }
  if (!found) return std::nullopt;
  const double tolerance = first / 8;
  // Entry edge: between `inside` (blocked or q) and `outside` (free).
  double blocked = inside, clear = outside;
  while (std::abs(clear - blocked) > tolerance) {
    const double mid = 0.5 * (blocked + clear);
    (free(mid) ? clear : blocked) = mid;
  }
  const double entry = clear;
  // Exit edge: keep going the same way until blocked (or sigma), then bisect.
  const double sign = outside > 0 ? 1 : -1;
  double last_free = outside, probe = outside;
  while (std::abs(probe) < options_.sigma) {
    probe = sign * std::min(options_.sigma, 2 * std::abs(probe));
    if (!free(probe)) break;
    last_free = probe;
  }
  double exit = last_free;
  if (probe != last_free) {
    double lo = last_free, hi = probe;
    while (std::abs(hi - lo) > tolerance) {
      const double mid = 0.5 * (lo + hi);
      (free(mid) ? lo : hi) = mid;
    }
    exit = lo;
  }
  const Eigen::VectorXd centre = at(0.5 * (entry + exit));
  if (!context_.checker.isValid(centre)) return std::nullopt;
  return centre;
}

void SvmpPlanner::makeRoadmap(PhaseTimes& times) {
  const auto t0 = Clock::now();
  nn_.emplace(roadmap_.nodes(), context_.space.metricScale());
  connectMilestones(roadmap_, *nn_, context_, options_.k);
  times.roadmap_ms += msSince(t0);
}

bool SvmpPlanner::repair(Roadmap& with_query, int start_node, int goal_node, cspace::Rng& rng) {
  // Frontier of a component: its node closest to a node outside it. Random configurations around the
  // segment between the two are guided down to the decision boundaries (thesis ch. 3.5).
  const Eigen::VectorXd& scale = context_.space.metricScale();
  std::vector<Eigen::VectorXd> starts;
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const int search = std::min(nn_->size(), 4 * options_.k + 1);
  for (int endpoint : {start_node, goal_node}) {
    double best = std::numeric_limits<double>::infinity();
    Eigen::VectorXd a, b;
    auto consider = [&](const Eigen::VectorXd& from) {
      for (int j : nn_->nearest(from, search)) {
        if (with_query.connected(endpoint, j)) continue;
        const double d = context_.space.distance(from, roadmap_.node(j));
        if (d < best) best = d, a = from, b = roadmap_.node(j);
        break;
      }
    };
    for (int i = 0; i < with_query.numNodes(); ++i)
      if (with_query.connected(endpoint, i)) consider(with_query.node(i));
    if (a.size() == 0) continue;
    const double spread = 0.5 * best;  // local to the disconnection: the pair is its narrowest point
    for (int s = 0; s < options_.repair_samples / 2; ++s) {
      Eigen::VectorXd q = a + unit(rng) * (b - a);
      for (int d = 0; d < q.size(); ++d) q[d] += spread * normal(rng) / scale[d];
      context_.space.clamp(q);
      starts.push_back(q);
    }
  }
  if (starts.empty()) return false;
  const int old_n = roadmap_.numNodes();
  if (addMilestones(starts, std::vector<int>(starts.size(), -1), true) == 0) return false;
  nn_.emplace(roadmap_.nodes(), scale);
  connectMilestones(roadmap_, *nn_, context_, options_.k, old_n);
  return true;
}

PlanResult SvmpPlanner::query(const cspace::Query& query, std::uint64_t seed) {
  PlanResult result;
  if (!checkEndpoints(context_, query, result)) return result;
  if (!nn_) throw std::invalid_argument("svmp: query before makeRoadmap");
  const auto t0 = Clock::now();
  cspace::Rng rng(seed ^ 0xA5A5A5A5ULL);
  for (int round = 0;; ++round) {
    Roadmap with_query = roadmap_;
    QueryOutcome outcome = queryRoadmap(with_query, *nn_, context_, query, options_.k);
    if (!outcome.path.empty()) {
      result.path = std::move(outcome.path);
      result.status = PlanStatus::kSolved;
      break;
    }
    if (round >= options_.repair_rounds ||
        !repair(with_query, outcome.start_node, outcome.goal_node, rng)) {
      int start_size = 0, goal_size = 0;
      for (int i = 0; i < with_query.numNodes(); ++i) {
        start_size += with_query.connected(i, outcome.start_node);
        goal_size += with_query.connected(i, outcome.goal_node);
      }
      result.status = PlanStatus::kFailed;
      result.message = "start and goal are not connected after " + std::to_string(round) +
                       " repair rounds (their components hold " + std::to_string(start_size) + " and " +
                       std::to_string(goal_size) + " of " + std::to_string(with_query.numNodes()) + " nodes)";
      break;
    }
  }
  result.times.query_ms = msSince(t0);
  return result;
}

PlanResult SvmpPlanner::solve(const cspace::Query& q, std::uint64_t seed) {
  clear();
  const auto checks0 = context_.checker.collisionChecks();
  const auto calls0 = context_.validator.calls();
  PlanResult result;
  PhaseTimes times;
  if (checkEndpoints(context_, q, result)) {
    try {
      sampleObstacle(seed, times);
      trainMultiSvm(times);
      findBoundaryMilestones(times);
      makeRoadmap(times);
      result = query(q, seed);
      times.query_ms = result.times.query_ms;
    } catch (const std::invalid_argument& e) {
      result.status = PlanStatus::kInvalidInput;
      result.message = e.what();
    }
  }
  result.times = times;
  result.milestones = roadmap_.numNodes();
  result.roadmap_edges = roadmap_.numEdges();
  result.support_vectors = supportVectors();
  result.collision_checks = context_.checker.collisionChecks() - checks0;
  result.local_planner_calls = context_.validator.calls() - calls0;
  return result;
}

}  // namespace svmp::planners
