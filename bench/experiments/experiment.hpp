#pragma once
// Runs each planner N times on one scenario (seeds S, S+1, ...), measures every returned path the same
// way (length, minimum clearance and strict correctness at a quarter of the checking resolution), and
// reports the thesis-style table and the JSON described in docs/architecture.md.
#include <ostream>
#include <string>
#include <vector>

#include "bench/experiments/driver_options.hpp"
#include "cspace/scenario/scenario.hpp"
#include "planners/plan_result.hpp"

namespace svmp::experiments {

struct RunRecord {
  planners::PlanResult result;
  int query = 0;             // index into the scenario's queries
  double time_ms = 0;        // wall time of solve() (first query: with the build)
  double path_length = 0;    // weighted metric, solved runs only
  double min_clearance = 0;  // FCL distance along the path at resolution / 4
  bool strict_correct = false;
};

struct PlannerRuns {
  std::string planner;
  std::vector<RunRecord> runs;
  int solved() const;
  int strictCorrect() const;
};

// Throws cspace::ScenarioError for unknown planners or bad parameters (before any run starts).
std::vector<PlannerRuns> runExperiment(const cspace::Scenario& scenario, const DriverOptions& options,
                                       std::ostream& log);
void printTable(const cspace::Scenario& scenario, const DriverOptions& options,
                const std::vector<PlannerRuns>& results, std::ostream& out);
// Written whole or not at all (temporary file, then rename). Throws std::runtime_error on failure.
void writeJson(const std::string& file, const cspace::Scenario& scenario, const DriverOptions& options,
               const std::vector<PlannerRuns>& results);

}  // namespace svmp::experiments
