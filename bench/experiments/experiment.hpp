#pragma once
// Runs each planner N times on one scenario (seeds S, S+1, ...), proves every returned path
// collision-free with the certified motion validator (a run is solved only when its path is), measures
// every path the same way (length, minimum clearance at a quarter of the checking resolution, OMPL's
// smoothness), optionally simplifies it, and reports the thesis-style table and the JSON described in
// docs/architecture.md (experiment.cpp runs, experiment_output.cpp writes).
#include <map>
#include <ostream>
#include <string>
#include <vector>

#include "bench/experiments/driver_options.hpp"
#include "bench/experiments/provenance.hpp"
#include "cspace/scenario/scenario.hpp"
#include "planners/plan_result.hpp"

namespace svmp::experiments {

struct RunRecord {
  planners::PlanResult result;
  std::uint64_t seed = 0;
  int query = 0;             // index into the scenario's queries
  double time_ms = 0;        // wall time of solve() (first query: with the build)
  double build_ms = 0;       // the build's share of time_ms (several queries, first query only)
  double path_length = 0;    // weighted metric, solved runs only (after simplification, when asked)
  double raw_length = 0;     // before simplification
  double smoothness = 0;     // OMPL's PathGeometric::smoothness of the final path
  double simplify_ms = 0;
  double min_clearance = 0;  // FCL distance along the path at resolution / 4
  double memory_mb = 0;      // growth of the process' resident memory over the call (allocators free lazily)
};

struct PlannerRuns {
  std::string planner;
  std::vector<RunRecord> runs;
  // Every parameter the planner read (its value, set or default) and those it derived from the
  // problem where the file left them unset (Planner::derivedParameters).
  std::map<std::string, std::string> parameters;
  int solved() const;     // solved, which with the driver's certifier means certified
  int certified() const;
};

// Builds every planner of `options` with the scenario's parameters and --set overrides, as a run would,
// and drops them: throws cspace::ScenarioError naming the planner, field and value (svmp-plan --check).
// With `out`, prints each planner's parameters: the value a run would use, whether it was set, left
// at its default or derived from the problem, and its range (svmp-plan --check).
void validatePlanners(const cspace::Scenario& scenario, const DriverOptions& options, std::ostream* out = nullptr);

// `count` start-goal pairs of configurations drawn uniformly (seeded) and valid under the exact
// checker, start != goal (svmp-plan --queries). Throws cspace::ScenarioError when 1000 draws in a row
// find no valid configuration.
std::vector<cspace::Query> randomQueries(const cspace::Scenario& scenario, int count, std::uint64_t seed);

// Several queries, or --queries (even one): one build per run answers them all.
bool sharedBuild(const cspace::Scenario& scenario, const DriverOptions& options);

// Throws cspace::ScenarioError for unknown planners or bad parameters (before any run starts).
std::vector<PlannerRuns> runExperiment(const cspace::Scenario& scenario, const DriverOptions& options,
                                       std::ostream& log);
void printTable(const cspace::Scenario& scenario, const DriverOptions& options,
                const std::vector<PlannerRuns>& results, std::ostream& out);
// Written whole or not at all (temporary file, then rename). Throws std::runtime_error on failure.
// `provenance`: what produced the runs (the code's revision, the machine, when they started).
void writeJson(const std::string& file, const cspace::Scenario& scenario, const DriverOptions& options,
               const std::vector<PlannerRuns>& results, const Provenance& provenance = Provenance::now());
// --paths: per planner and run, the status, seed, query and the path's waypoints (JSON, whole or not at all).
void writePathsJson(const std::string& file, const cspace::Scenario& scenario,
                    const std::vector<PlannerRuns>& results);
// --path-dir: DIR/<scenario>_<planner>_seed<S>[_query<i>].txt per solved run, OMPL's
// PathGeometric::printAsMatrix format (one configuration a line, coordinates separated by spaces).
void writePathMatrices(const std::string& dir, const cspace::Scenario& scenario,
                       const std::vector<PlannerRuns>& results, std::ostream& log);

}  // namespace svmp::experiments
