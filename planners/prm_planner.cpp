#include "planners/prm_planner.hpp"

#include <chrono>

#include "planners/nearest_neighbors.hpp"
#include "planners/roadmap_builder.hpp"

namespace svmp::planners {

PrmPlanner::PrmPlanner(const PlanningContext& context, PrmOptions options)
    : context_(context), options_(options) {}

PlanResult PrmPlanner::solve(const cspace::Query& query, std::uint64_t seed) {
  clear();
  const auto checks0 = context_.checker.collisionChecks();
  const auto calls0 = context_.validator.calls();
  PlanResult result;
  if (checkEndpoints(context_, query, result)) {
    auto t0 = Clock::now();
    // Draw all samples from one generator first, then test them in parallel: the milestone set does
    // not depend on the thread count.
    cspace::Rng rng(seed);
    std::vector<Eigen::VectorXd> candidates(options_.samples);
    for (auto& q : candidates) q = context_.space.sampleUniform(rng);
    std::vector<char> free(candidates.size());
#pragma omp parallel for schedule(static) num_threads(context_.threads)
    for (int i = 0; i < options_.samples; ++i) free[i] = context_.checker.isValid(candidates[i]);
    for (int i = 0; i < options_.samples; ++i)
      if (free[i]) roadmap_.addNode(candidates[i]);
    result.times.sampling_ms = msSince(t0);

    t0 = Clock::now();
    const NearestNeighbors nn(roadmap_.nodes(), context_.space.metricScale());
    connectMilestones(roadmap_, nn, context_, options_.k);
    result.times.roadmap_ms = msSince(t0);

    t0 = Clock::now();
    Roadmap with_query = roadmap_;
    QueryOutcome outcome = queryRoadmap(with_query, nn, context_, query, options_.k);
    result.times.query_ms = msSince(t0);
    result.path = std::move(outcome.path);
    result.status = result.path.empty() ? PlanStatus::kFailed : PlanStatus::kSolved;
    if (!result.solved()) result.message = "start and goal are not connected by the roadmap";
  }
  result.milestones = roadmap_.numNodes();
  result.roadmap_edges = roadmap_.numEdges();
  result.collision_checks = context_.checker.collisionChecks() - checks0;
  result.local_planner_calls = context_.validator.calls() - calls0;
  return result;
}

}  // namespace svmp::planners
