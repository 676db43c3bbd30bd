#include "planners/prm_planner.hpp"

#include <atomic>

#include "cspace/parallel_for.hpp"
#include "planners/planner_registry.hpp"
#include "planners/roadmap_builder.hpp"

namespace svmp::planners {

PrmOptions PrmOptions::fromParameters(const cspace::ParameterSet& params) {
  PrmOptions o;
  // A milestone with its k edges costs a few hundred bytes: 2e6 stays below a GB.
  o.samples = static_cast<int>(params.getInt("samples", o.samples, 1, 2000000));
  o.k = static_cast<int>(params.getInt("k", o.k, 1, 10000));
  return o;
}

std::string PrmOptions::validate() const {
  if (samples < 1 || samples > 2000000) return "samples must be in [1, 2e6], got " + std::to_string(samples);
  if (k < 1) return "k must be >= 1, got " + std::to_string(k);
  return "";
}

SVMP_REGISTER_PLANNER("prm", [](const PlanningContext& context, const cspace::ParameterSet& params) {
  return std::make_unique<PrmPlanner>(context, PrmOptions::fromParameters(params));
});

PrmPlanner::PrmPlanner(const PlanningContext& context, PrmOptions options)
    : Planner(context), options_(options) {
  if (const std::string err = options_.validate(); !err.empty()) throw std::invalid_argument("prm: " + err);
}

void PrmPlanner::clear() {
  forgetBuild();
  roadmap_.clear();
  with_query_.clear();
  nn_.reset();
}

void PrmPlanner::buildRoadmap(std::uint64_t seed, const Termination& stop, PlanResult& result) {
  auto t0 = Clock::now();
  // Draw all samples from one generator first, then test them in parallel: the milestone set does not
  // depend on the thread count.
  cspace::Rng rng(seed);
  std::atomic<bool> stopped{false};
  std::vector<Eigen::VectorXd> candidates;
  for (int i = 0; i < options_.samples && !stopped; ++i) {
    if ((i & 4095) == 0 && stop()) stopped = true;
    candidates.push_back(context_.space.sampleUniform(rng));
  }
  const int n = static_cast<int>(candidates.size());
  std::vector<char> free(n);
  cspace::parallelFor(n, context_.threads, 64, [&](int i) {
    if (stopped.load(std::memory_order_relaxed) || ((i & 63) == 0 && stop() && (stopped = true))) return;
    free[i] = context_.checker.isValid(candidates[i]);
  });
  for (int i = 0; i < n && !stopped; ++i)
    if (free[i]) roadmap_.addNode(candidates[i]);
  result.times.sampling_ms += msSince(t0);

  t0 = Clock::now();
  bool done = !stopped;
  if (done) {
    nn_.emplace(roadmap_.nodes(), context_.space.metricScale());
    done = connectMilestones(roadmap_, *nn_, context_, options_.k, 0, stop);
  }
  result.times.roadmap_ms += msSince(t0);
  result.status = done ? PlanStatus::kSolved : PlanStatus::kTimeout;
  if (!done) result.message = "time limit reached while building the roadmap";
  result.milestones = roadmap_.numNodes();
  result.roadmap_edges = roadmap_.numEdges();
}

void PrmPlanner::answer(const cspace::Query& query, std::uint64_t, const Termination& stop, PlanResult& result) {
  const auto t0 = Clock::now();
  with_query_ = roadmap_;
  QueryOutcome outcome =
      queryRoadmap(with_query_, *nn_, context_, query, options_.k, &roadmap_, !blocked_motion_);
  result.times.query_ms += msSince(t0);
  result.path = std::move(outcome.path);
  result.certified = outcome.certified;
  result.times.certify_ms += outcome.certify_ms;
  // A check the limit cut short is no proof of a disconnection.
  result.status = !result.path.empty() ? PlanStatus::kSolved : stop() ? PlanStatus::kTimeout : PlanStatus::kFailed;
  if (result.status == PlanStatus::kTimeout) result.message = "time limit reached during the query";
  if (result.status == PlanStatus::kFailed) result.message = "start and goal are not connected by the roadmap";
  result.milestones = roadmap_.numNodes();
  result.roadmap_edges = roadmap_.numEdges();
}

}  // namespace svmp::planners
