#pragma once
// What every planner returns (docs/architecture.md, "Results and counters"): a status, the path and named counters.
#include <Eigen/Core>
#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

namespace svmp::planners {

enum class PlanStatus {
  kSolved,
  kFailed,
  kTimeout,
  kInvalidStart,
  kInvalidGoal,
  kInvalidInput,
  kLocalMinimum  // a potential-field descent stopped making progress (local planner)
};

const char* planStatusName(PlanStatus status);

using Clock = std::chrono::steady_clock;
inline double msSince(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

struct PhaseTimes {
  double sampling_ms = 0, training_ms = 0, milestones_ms = 0, roadmap_ms = 0, query_ms = 0;
  double certify_ms = 0;  // proving path segments free (part of query_ms for roadmap planners)
  double total() const { return sampling_ms + training_ms + milestones_ms + roadmap_ms + query_ms; }
  PhaseTimes& operator+=(const PhaseTimes& o) {
    sampling_ms += o.sampling_ms, training_ms += o.training_ms, milestones_ms += o.milestones_ms;
    roadmap_ms += o.roadmap_ms, query_ms += o.query_ms, certify_ms += o.certify_ms;
    return *this;
  }
};

struct PlanResult {
  PlanStatus status = PlanStatus::kFailed;  // of Planner::build(): kSolved means ready for queries
  std::string message;                // why, when not solved
  std::vector<Eigen::VectorXd> path;  // start ... goal, straight segments between
  bool certified = false;             // every segment proven free by the context's certifier
  std::uint64_t certified_segments = 0;  // certifier calls (segments proven or disproved)
  std::uint64_t collision_checks = 0;
  std::uint64_t local_planner_calls = 0;
  std::uint64_t distance_queries = 0;  // FCL distance queries (certification)
  // Proxy checkers only (PlanningContext::repairer): stretches of the path replanned on the exact
  // checker, and the exact checks of verification and repair.
  int repaired_stretches = 0;
  std::uint64_t exact_checks = 0;
  std::uint64_t milestones = 0;
  std::uint64_t roadmap_edges = 0;
  std::uint64_t support_vectors = 0;
  PhaseTimes times;
  // Spent only to fill the counters above from a planner that does not keep them (an OMPL planner's
  // roadmap copied out to count it): not the planner's work, so the driver leaves it out of the time.
  double counting_ms = 0;
  // What the planner left out of its input, for the user to see (SVMP: obstacles it has no sample
  // of, and why: beyond the robot's reach, no configuration found hitting them).
  std::vector<std::string> warnings;
  bool solved() const { return status == PlanStatus::kSolved; }
};

// Folds a build's counters and phase times into the result of the query answered on it, so that one
// record carries what the whole answer cost (a build answers no query: its query_ms is 0).
inline void addBuild(const PlanResult& build, PlanResult& query) {
  query.collision_checks += build.collision_checks;
  query.local_planner_calls += build.local_planner_calls;
  query.distance_queries += build.distance_queries;
  query.certified_segments += build.certified_segments;
  query.times += build.times;
  query.warnings.insert(query.warnings.begin(), build.warnings.begin(), build.warnings.end());
}

}  // namespace svmp::planners
