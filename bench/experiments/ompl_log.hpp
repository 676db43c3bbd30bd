#pragma once
// svmp-plan --ompl-log: every run of every planner in the log format of OMPL's benchmarking (OMPL 1.5,
// ompl::tools::Benchmark::saveResultsToStream, src/ompl/tools/benchmark/src/Benchmark.cpp), which
// ompl_benchmark_statistics (ompl-demos) turns into the SQLite database Planner Arena
// (plannerarena.org) reads. Experiment: the scenario's name, its file, dof, queries, threads,
// checker, resolution and simplifier as experiment properties; host, start date, CPU; the first seed,
// the time limit (inf: none), no memory limit (inf), runs per planner, total time.
// Per planner (its registry name) the parameters as "common properties" (the value each key had,
// default or set), per run OMPL's properties: time REAL (s, build included for the first query of a
// run), memory REAL (MB, growth of resident memory over the run), status ENUM (OMPL's
// PlannerStatus, planners/ompl/state_bridge.hpp omplStatus), solved BOOLEAN (= certified), and for
// solved runs approximate solution, solution difference, length, smoothness, clearance (FCL distance
// along the path at resolution / 4), segments, correct solution and correct solution strict (both the
// certificate, which is stronger than OMPL's sampled check), with --simplify the "simplified
// solution" properties and the simplification time; graph states / motions (milestones, roadmap
// edges). Ours besides: seed, query, svmp status, collision checks, local planner calls, distance
// queries, certified segments, repaired stretches, exact checks, support vectors, milestones (as graph
// states; svmp-ompl-benchmark records it too), and the phase times (s) of build, sampling, training,
// milestones, roadmap, query and certification.
#include <map>
#include <string>
#include <vector>

#include "bench/experiments/driver_options.hpp"
#include "bench/experiments/experiment.hpp"
#include "cspace/scenario/scenario.hpp"

namespace svmp::experiments {

struct ExperimentTiming {
  std::string started;  // "YYYY-MM-DD HH:MM:SS" (UTC)
  double seconds = 0;   // wall time of all runs
};

// The log as text; writeOmplLog writes it whole or not at all (std::runtime_error).
std::string omplLogText(const cspace::Scenario& scenario, const DriverOptions& options,
                        const std::vector<PlannerRuns>& results, const ExperimentTiming& timing);
void writeOmplLog(const std::string& file, const cspace::Scenario& scenario, const DriverOptions& options,
                  const std::vector<PlannerRuns>& results, const ExperimentTiming& timing);
// Our counters of one result as OMPL run properties ("name TYPE" -> value): svmp status, local planner
// calls, distance queries, certified segments, repaired stretches, exact checks, support vectors,
// milestones (svmp-ompl-benchmark records them for our planners too).
std::map<std::string, std::string> counterProperties(const planners::PlanResult& result);

}  // namespace svmp::experiments
