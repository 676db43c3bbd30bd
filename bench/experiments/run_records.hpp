#pragma once
// Per-run records in svmp-plan's JSON and the merge of shard files (svmp-plan --merge, scripts/sweep).
// A sweep splits one run over seeds S..S+N-1 into shards with their own --seed and --runs; each shard's
// JSON carries every run's record (counters and measurements at full double precision), so merging
// rebuilds the PlannerRuns of the single run and the driver's own printTable and writeJson recompute
// its table and aggregates: one implementation, and the merged numbers equal the single run's.
#include <string>
#include <vector>

#include "bench/experiments/driver_options.hpp"
#include "bench/experiments/experiment.hpp"
#include "cspace/scenario/scenario.hpp"

namespace svmp::experiments {

// One run's record as a JSON object (one line; doubles written so they read back bit for bit).
std::string runRecordJson(const RunRecord& record);
// The --set overrides as the JSON array of "PLANNER.KEY=VALUE" strings.
std::string overridesJson(const DriverOptions& options);

struct MergedShards {
  cspace::Scenario scenario;  // loaded from the shards' "file" (or the given override)
  DriverOptions options;      // runs and seed span the union of the shards; the rest as the shards had it
  std::vector<PlannerRuns> results;  // planners in order of first appearance, records in (seed, query) order
  Provenance provenance;             // the shards': their revision (one), their machines (each listed once)
};

// Reads shard JSON files written by svmp-plan --json and merges them as one run over the union of
// their seeds. Throws std::runtime_error naming the file, field and value when a file is unreadable or
// not svmp-plan's JSON, when shards disagree (scenario, dof, threads, checker, simplifier, a planner's
// --set values), when a planner's seeds overlap or leave a gap, when planners cover different seeds,
// or when shards with different --seed drew --queries or trained a proxy checker from it. `scenario_file` non-empty: load it instead of the shards' "file" (its name must match).
MergedShards mergeShards(const std::vector<std::string>& files, const std::string& scenario_file);

}  // namespace svmp::experiments
