#pragma once
// The common interface of every planner (docs/architecture.md): the context they share (one scenario's
// space, validity checker and motion validator, so counts are comparable), the build / query / clear
// separation that makes a roadmap answer many queries, a termination condition every planner honours,
// and what a planner shows of itself (PlannerView) for pictures. Planners register by name in
// planners/planner_registry.hpp.
//
// Errors: planning failures (no path, time out, a start in collision, too few obstacle classes) are
// statuses in PlanResult; exceptions are for misuse (query before build, std::logic_error) and bad
// input (cspace::ScenarioError from the factories).
//
// Thread safety: a planner is used by one thread at a time; it may use context.threads OpenMP threads
// inside a call, never sharing mutable FCL objects, generators or scratch buffers between them.
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cspace/configuration_space.hpp"
#include "cspace/motion_validator.hpp"
#include "planners/obstacle_sampler.hpp"
#include "cspace/scenario/scenario.hpp"
#include "cspace/validity_checker.hpp"
#include "planners/plan_result.hpp"
#include "planners/termination.hpp"

namespace svmp::planners {

class PathRepairer;
class RiskFunction;
class Roadmap;
struct SvppTrace;

struct PlanningContext {
  const cspace::ConfigurationSpace& space;
  const cspace::ValidityChecker& checker;
  const cspace::MotionValidator& validator;
  int threads = 1;
  // Proves the segments of returned paths collision-free (cspace/certified_motion_validator.hpp). When
  // set, a planner reports kSolved only for a path whose every segment it proved: roadmap planners
  // drop a disproved edge and search again, the others fail the query. Null: no certification.
  const cspace::MotionValidator* certifier = nullptr;
  // When the checker is a learned proxy: verifies a non-roadmap planner's path with the exact checker
  // and replans its invalid stretches there (planners/verify_repair.hpp); the certifier then proves
  // segments with the exact checker too. Null: the checker is exact.
  const PathRepairer* repairer = nullptr;
};

// What a planner learned, for pictures and inspection; null where it has none.
struct PlannerView {
  const planners::ObstacleSamples* samples = nullptr;  // labelled samples (obstacle ids, or 1/2 for classes)
  const RiskFunction* risk = nullptr;                // decision functions F_k
  const Roadmap* roadmap = nullptr;
  const SvppTrace* svpp = nullptr;                   // SVPP's patterns tried (planners/svpp_planner.hpp)
};

class Planner {
 public:
  explicit Planner(const PlanningContext& context) : context_(context) {}
  virtual ~Planner() = default;
  virtual std::string name() const = 0;

  // Learns what does not depend on a query (roadmap, models); every random choice flows from `seed`.
  // The result's status is kSolved when the planner is ready for queries, else why not (kTimeout,
  // kFailed, kInvalidInput); its counters and times cover the construction. Planners with nothing to
  // learn ahead return kSolved at once.
  PlanResult build(std::uint64_t seed, const Termination& stop = {});
  // Answers one query on what build() learned (throws std::logic_error before a successful build).
  // May grow the roadmap (repair); clearQuery() undoes nothing learned, it only forgets query state.
  PlanResult query(const cspace::Query& query, std::uint64_t seed, const Termination& stop = {});
  virtual void clearQuery() {}
  // Forgets everything learned; the next query needs a new build().
  virtual void clear() = 0;
  // clear(), build() and query() in one: counters, times and status cover all of it. A roadmap
  // planner (triesStraightMotionFirst) whose query's straight motion is free and proven returns it
  // without a build: the path its query would have returned first; then answerBeforeBuild may answer.
  PlanResult solve(const cspace::Query& query, std::uint64_t seed, const Termination& stop = {});

  virtual PlannerView view() const { return {}; }
  bool built() const { return built_; }
  // The values a planner derived from the problem for parameters the file left unset (name -> value
  // as text: svmp's sigma and step, svpp's lengths), so a result file records what ran.
  virtual std::map<std::string, std::string> derivedParameters() const { return {}; }

 protected:
  // The planner's steps; the base class counts checks and calls around them and checks the query's
  // end points before answer() runs.
  virtual void buildRoadmap(std::uint64_t seed, const Termination& stop, PlanResult& result) = 0;
  virtual void answer(const cspace::Query& query, std::uint64_t seed, const Termination& stop,
                      PlanResult& result) = 0;
  // Called after clear() by subclasses.
  void forgetBuild() { built_ = false; }
  // With a certifier: proves each segment of a solved, not yet certified result; the first that fails
  // turns the result into kFailed (message names it, path cleared). With a repairer, for a planner
  // whose paths may be repaired: verify and repair instead, failing only when a stretch cannot be
  // repaired.
  void certify(PlanResult& result, std::uint64_t seed, const Termination& stop) const;
  // False for planners whose path is the method's own answer (the thesis' local planner, SVPP's
  // separating surface): a stretch replanned by another planner would no longer be theirs.
  virtual bool repairable() const { return true; }
  // True for the roadmap planners, whose query begins with the straight motion (queryRoadmap).
  virtual bool triesStraightMotionFirst() const { return false; }
  // Called by solve() after a blocked straight motion, before the build: true when `result` is final
  // without one (solved, its path proven with a certifier, or the time limit reached).
  virtual bool answerBeforeBuild(const cspace::Query&, std::uint64_t, const Termination&, PlanResult&) {
    return false;
  }
  // Set by solve() to its query when the straight motion was tried before the build and failed: the
  // query need not try it again (it stays blocked, or unproven, on the same obstacles), and the build
  // may look for obstacles along it (SVMP's roots). Empty in build() and query().
  std::optional<cspace::Query> blocked_motion_;

  PlanningContext context_;

 private:
  bool built_ = false;
};

// Start and goal must have the space's dimension and be valid, else the status says which (naming the
// obstacle hit).
bool checkEndpoints(const PlanningContext& context, const cspace::Query& query, PlanResult& result);

}  // namespace svmp::planners
