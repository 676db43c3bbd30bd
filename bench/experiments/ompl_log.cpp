#include "bench/experiments/ompl_log.hpp"

#include <cmath>
#include <map>
#include <sstream>

#include "bench/experiments/atomic_file.hpp"
#include "bench/experiments/provenance.hpp"
#include "cspace/scenario/parameters.hpp"
#include "planners/ompl/state_bridge.hpp"

namespace svmp::experiments {
namespace {

namespace ob = ::ompl::base;

std::string real(double v) { return cspace::parameterText(v); }
std::string integer(std::uint64_t v) { return std::to_string(v); }
std::string boolean(bool v) { return v ? "1" : "0"; }

// One line of a log's property values: no "; " may occur inside a value, nor a line break.
std::string cleanValue(std::string text) {
  for (char& c : text)
    if (c == ';' || c == '\n' || c == '\r') c = ',';
  return text;
}

using Properties = std::map<std::string, std::string>;  // "name TYPE" -> value

Properties runProperties(const RunRecord& r, bool simplified) {
  const planners::PlanResult& result = r.result;
  Properties p;
  p["time REAL"] = real(r.time_ms / 1000);
  p["memory REAL"] = real(r.memory_mb);
  p["status ENUM"] = std::to_string(static_cast<int>(
      static_cast<ob::PlannerStatus::StatusType>(ompl_planners::omplStatus(result.status))));
  p["solved BOOLEAN"] = boolean(result.solved());
  if (result.solved()) {
    const std::string segments = integer(result.path.size() - 1);
    p["approximate solution BOOLEAN"] = "0";
    p["solution difference REAL"] = "0";
    p["solution length REAL"] = real(r.raw_length);
    p["correct solution BOOLEAN"] = boolean(result.certified);
    p["correct solution strict BOOLEAN"] = boolean(result.certified);
    const std::string prefix = simplified ? "simplified " : "";
    if (simplified) {
      p["simplification time REAL"] = real(r.simplify_ms / 1000);
      p["simplified solution length REAL"] = real(r.path_length);
      p["simplified correct solution BOOLEAN"] = boolean(result.certified);
      p["simplified correct solution strict BOOLEAN"] = boolean(result.certified);
    }
    p[prefix + "solution smoothness REAL"] = real(r.smoothness);
    p[prefix + "solution clearance REAL"] = real(r.min_clearance);
    p[prefix + "solution segments INTEGER"] = segments;
  }
  p["graph states INTEGER"] = integer(result.milestones);
  p["graph motions INTEGER"] = integer(result.roadmap_edges);
  p["seed INTEGER"] = integer(r.seed);
  p["query INTEGER"] = std::to_string(r.query);
  p.merge(counterProperties(result));
  p["collision checks INTEGER"] = integer(result.collision_checks);
  p["build time REAL"] = real(r.build_ms / 1000);
  p["sampling time REAL"] = real(result.times.sampling_ms / 1000);
  p["training time REAL"] = real(result.times.training_ms / 1000);
  p["milestones time REAL"] = real(result.times.milestones_ms / 1000);
  p["roadmap time REAL"] = real(result.times.roadmap_ms / 1000);
  p["query time REAL"] = real(result.times.query_ms / 1000);
  p["certify time REAL"] = real(result.times.certify_ms / 1000);
  return p;
}

}  // namespace

Properties counterProperties(const planners::PlanResult& result) {
  return {{"svmp status TEXT", planners::planStatusName(result.status)},
          {"local planner calls INTEGER", integer(result.local_planner_calls)},
          {"distance queries INTEGER", integer(result.distance_queries)},
          {"certified segments INTEGER", integer(result.certified_segments)},
          {"repaired stretches INTEGER", std::to_string(result.repaired_stretches)},
          {"exact checks INTEGER", integer(result.exact_checks)},
          {"support vectors INTEGER", integer(result.support_vectors)},
          {"milestones INTEGER", integer(result.milestones)}};
}

std::string omplLogText(const cspace::Scenario& scenario, const DriverOptions& options,
                        const std::vector<PlannerRuns>& results, const ExperimentTiming& timing) {
  const std::string simplifier = !options.simplify ? "none" : options.simplify_svm ? "svpp" : "shortcut";
  std::ostringstream o;
  // The library that wrote it: ompl_benchmark_statistics records "svmp <the line's last word>", here
  // the version and the git revision of the code (provenance.hpp). The format is OMPL's.
  o << "svmp version " << SVMP_VERSION << "-" << sourceRevision() << "\n";
  o << "Experiment " << cleanValue(scenario.name.empty() ? "NO_NAME" : scenario.name) << "\n";
  const Properties experiment = {{"scenario_file TEXT", scenario.path},
                                 {"dof INTEGER", std::to_string(scenario.robot->dof())},
                                 {"queries INTEGER", std::to_string(scenario.queries.size())},
                                 {"threads INTEGER", std::to_string(options.threads)},
                                 {"checker TEXT", options.checker},
                                 {"resolution REAL", real(scenario.resolution)},
                                 {"simplifier TEXT", simplifier}};
  o << experiment.size() << " experiment properties\n";
  for (const auto& [key, value] : experiment) o << key << " = " << cleanValue(value) << "\n";
  o << "Running on " << hostName() << "\n";
  o << "Starting at " << timing.started << "\n";
  o << "<<<|\n"
    << "svmp-plan on " << scenario.path << ": " << scenario.robot->name() << ", dof " << scenario.robot->dof()
    << ", " << scenario.environment->size() << " obstacles, resolution " << scenario.resolution << ", "
    << scenario.queries.size() << " queries; runs use seeds " << options.seed << ".."
    << options.seed + options.runs - 1 << ", checker " << options.checker << ", simplifier " << simplifier << ".\n"
    << "Solved means certified collision-free (cspace/certified_motion_validator.hpp); times in seconds.\n"
    << "|>>>\n";
  o << "<<<|\n" << cpuInfo() << "\n|>>>\n";
  o << options.seed << " is the random seed\n";
  o << (options.time_limit > 0 ? real(options.time_limit) : "inf") << " seconds per run\n";
  o << "inf MB per run\n";
  o << options.runs << " runs per planner\n";
  o << real(timing.seconds) << " seconds spent to collect the data\n";
  o << "1 enum type\nstatus";
  for (int i = 0; i < ob::PlannerStatus::TYPE_COUNT; ++i)
    o << '|' << ob::PlannerStatus(static_cast<ob::PlannerStatus::StatusType>(i)).asString();
  o << "\n" << results.size() << " planners\n";
  for (const PlannerRuns& runs : results) {
    o << runs.planner << "\n" << runs.parameters.size() << " common properties\n";
    for (const auto& [key, value] : runs.parameters) o << key << " = " << cleanValue(value) << "\n";
    std::vector<Properties> rows;
    std::map<std::string, bool> names;
    for (const RunRecord& r : runs.runs) {
      rows.push_back(runProperties(r, options.simplify));
      for (const auto& [name, value] : rows.back()) names[name] = true;
    }
    o << names.size() << " properties for each run\n";
    for (const auto& [name, seen] : names) o << name << "\n";
    o << rows.size() << " runs\n";
    for (const Properties& row : rows) {
      for (const auto& [name, seen] : names) {
        const auto it = row.find(name);
        if (it != row.end()) o << cleanValue(it->second);
        o << "; ";
      }
      o << "\n";
    }
    o << ".\n";
  }
  return o.str();
}

void writeOmplLog(const std::string& file, const cspace::Scenario& scenario, const DriverOptions& options,
                  const std::vector<PlannerRuns>& results, const ExperimentTiming& timing) {
  writeFileAtomically(file, omplLogText(scenario, options, results, timing));
}

}  // namespace svmp::experiments
