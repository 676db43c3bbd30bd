#include "planners/planner.hpp"

#include <stdexcept>

#include "planners/verify_repair.hpp"

namespace svmp::planners {
namespace {

// One counter scope for every planner: what the checker and validator counted between construction and
// finish() goes into the result.
class CounterScope {
 public:
  explicit CounterScope(const PlanningContext& c)
      : context_(c),
        checks_(c.checker.collisionChecks()),
        calls_(c.validator.calls()),
        certifier_calls_(c.certifier ? c.certifier->calls() : 0),
        distances_(c.certifier ? c.certifier->distanceQueries() : 0) {}
  void finish(PlanResult& result) const {
    result.collision_checks += context_.checker.collisionChecks() - checks_;
    result.local_planner_calls += context_.validator.calls() - calls_;
    if (!context_.certifier) return;
    result.certified_segments += context_.certifier->calls() - certifier_calls_;
    result.distance_queries += context_.certifier->distanceQueries() - distances_;
  }

 private:
  const PlanningContext& context_;
  std::uint64_t checks_, calls_, certifier_calls_, distances_;
};

// The straight motion from start to goal, checked and (with a certifier) proven: the path when both
// pass.
bool straightMotionAnswers(const PlanningContext& context, const cspace::Query& query, PlanResult& result) {
  auto t0 = Clock::now();
  const bool free = context.validator.isValid(query.start, query.goal);
  result.times.query_ms += msSince(t0);
  if (!free) return false;
  if (context.certifier) {
    t0 = Clock::now();
    const bool proven = context.certifier->isValid(query.start, query.goal);
    result.times.certify_ms += msSince(t0);
    if (!proven) return false;
  }
  result.status = PlanStatus::kSolved;
  result.path = {query.start, query.goal};
  result.certified = context.certifier != nullptr;
  return true;
}

}  // namespace

const char* planStatusName(PlanStatus status) {
  switch (status) {
    case PlanStatus::kSolved: return "solved";
    case PlanStatus::kFailed: return "failed";
    case PlanStatus::kTimeout: return "timeout";
    case PlanStatus::kInvalidStart: return "invalid_start";
    case PlanStatus::kInvalidGoal: return "invalid_goal";
    case PlanStatus::kInvalidInput: return "invalid_input";
    case PlanStatus::kLocalMinimum: return "local_minimum";
  }
  return "?";
}

bool checkEndpoints(const PlanningContext& context, const cspace::Query& query, PlanResult& result) {
  if (query.start.size() != context.space.dim() || query.goal.size() != context.space.dim()) {
    result.status = PlanStatus::kInvalidInput;
    result.message = "query size differs from the configuration space's dimension";
    return false;
  }
  // Whether the query is valid is the problem's question, not a learned proxy's: a proxy that has not
  // converged may predict a free goal in collision, and the planner must then try (and may fail), not
  // report the query invalid.
  const cspace::ValidityChecker& judge = context.repairer ? context.repairer->exactContext().checker : context.checker;
  if (const int hit = judge.check(query.start); hit != cspace::kFree) {
    result.status = PlanStatus::kInvalidStart;
    result.message = "start is " + cspace::describeHit(judge.environment(), hit);
    return false;
  }
  if (const int hit = judge.check(query.goal); hit != cspace::kFree) {
    result.status = PlanStatus::kInvalidGoal;
    result.message = "goal is " + cspace::describeHit(judge.environment(), hit);
    return false;
  }
  return true;
}

void Planner::certify(PlanResult& result, std::uint64_t seed, const Termination& stop) const {
  if (!context_.certifier || !result.solved() || result.certified) return;
  const auto t0 = Clock::now();
  if (context_.repairer && repairable()) {
    RepairStats stats;
    std::string why;
    result.certified = context_.repairer->verifyAndRepair(result.path, name(), seed, stop, stats, why);
    result.times.certify_ms += msSince(t0);
    result.repaired_stretches += stats.invalid_stretches;
    result.exact_checks += stats.exact_checks;
    if (result.certified) return;
    result.status = stop() ? PlanStatus::kTimeout : PlanStatus::kFailed;  // a repair the limit cut short
    result.message = why;
    result.path.clear();
    return;
  }
  size_t i = 0;
  while (i + 1 < result.path.size() && context_.certifier->isValid(result.path[i], result.path[i + 1])) ++i;
  result.times.certify_ms += msSince(t0);
  result.certified = i + 1 >= result.path.size();
  if (result.certified) return;
  result.status = PlanStatus::kFailed;
  result.message = "segment " + std::to_string(i) + " of the path is not proven collision-free";
  result.path.clear();
}

PlanResult Planner::build(std::uint64_t seed, const Termination& stop) {
  clear();
  blocked_motion_.reset();
  const cspace::MotionStopScope motion_stop(stop.asFunction());
  const CounterScope scope(context_);
  PlanResult result;
  buildRoadmap(seed, stop, result);
  built_ = result.solved();
  scope.finish(result);
  return result;
}

PlanResult Planner::query(const cspace::Query& q, std::uint64_t seed, const Termination& stop) {
  if (!built_) throw std::logic_error(name() + ": query() before a successful build()");
  const cspace::MotionStopScope motion_stop(stop.asFunction());
  clearQuery();
  blocked_motion_.reset();
  const CounterScope scope(context_);
  PlanResult result;
  if (checkEndpoints(context_, q, result)) {
    answer(q, seed, stop, result);
    certify(result, seed, stop);
  }
  scope.finish(result);
  return result;
}

PlanResult Planner::solve(const cspace::Query& q, std::uint64_t seed, const Termination& stop) {
  clear();
  const cspace::MotionStopScope motion_stop(stop.asFunction());
  blocked_motion_.reset();
  const CounterScope scope(context_);
  PlanResult result;
  if (checkEndpoints(context_, q, result)) {
    if (triesStraightMotionFirst() && !straightMotionAnswers(context_, q, result)) blocked_motion_ = q;
    // A limit that fires during the motion's check ends the run here, saying so (the check reports
    // the motion blocked), and a path it found stands.
    if (blocked_motion_ && stop()) {
      result.status = PlanStatus::kTimeout;
      result.message = "time limit reached while checking the straight start-goal motion";
    } else if (!result.solved() && blocked_motion_ && answerBeforeBuild(q, seed, stop, result)) {
      certify(result, seed, stop);  // proven already when solved; a no-op then
    } else if (!result.solved()) {
      buildRoadmap(seed, stop, result);
      built_ = result.solved();
      if (built_) {
        result.status = PlanStatus::kFailed;
        answer(q, seed, stop, result);
        certify(result, seed, stop);
      }
    }
  }
  scope.finish(result);
  return result;
}

}  // namespace svmp::planners
