// What runExperiment measured, as svmp-plan writes it: the thesis-style table, the JSON of every
// run, the paths as JSON and as OMPL's matrix text files.
#include "bench/experiments/experiment.hpp"

#include <iomanip>
#include <sstream>

#include "bench/experiments/atomic_file.hpp"
#include "bench/experiments/output_text.hpp"
#include "bench/experiments/run_records.hpp"

namespace svmp::experiments {
namespace {

template <class F>
Stats collect(const PlannerRuns& runs, bool solved_only, F field) {
  std::vector<double> v;
  for (const auto& r : runs.runs)
    if (!solved_only || r.result.solved()) v.push_back(field(r));
  return statsOf(v);
}

// The build time of each run (carried by its first query's record).
std::vector<double> buildTimes(const PlannerRuns& runs) {
  std::vector<double> builds;
  for (const RunRecord& r : runs.runs)
    if (r.query == 0) builds.push_back(r.build_ms);
  return builds;
}

}  // namespace

void printTable(const cspace::Scenario& scenario, const DriverOptions& options,
                const std::vector<PlannerRuns>& results, std::ostream& out) {
  out << "\n" << scenario.name << " (dof " << scenario.robot->dof() << "), " << options.runs << " runs"
      << (sharedBuild(scenario, options) ? " x " + std::to_string(scenario.queries.size()) + " queries" : "")
      << ", seeds " << options.seed << ".." << options.seed + options.runs - 1 << ", " << options.threads
      << " thread(s)" << (!options.simplify ? "" : options.simplify_svm ? ", paths SVM-smoothed" : ", paths simplified")
      << "\n";
  if (options.checker != "fcl")
    out << "checker " << options.checker << " (learned proxy; every path verified on FCL, failing stretches replanned)\n";
  out << "mean ± std over all runs (path length and clearance over solved runs); solved = certified "
         "collision-free; CD = collision checks, LP = local planner calls, DQ = distance queries "
         "(certification)\n";
  const int w = 20;
  out << std::left << std::setw(17) << "planner" << std::setw(9) << "solved" << std::setw(w) << "CD"
      << std::setw(w) << "LP" << std::setw(w) << "DQ" << std::setw(w) << "milestones" << std::setw(w)
      << "time (ms)" << std::setw(w) << "path length" << (options.simplify ? pad("raw length", w) : "")
      << "min clearance\n";
  for (const auto& runs : results) {
    std::ostringstream solved;
    solved << runs.solved() << "/" << runs.runs.size();
    out << pad(runs.planner, 17) << pad(solved.str(), 9)
        << pad(meanStd(collect(runs, false, [](const RunRecord& r) { return double(r.result.collision_checks); }), 0), w)
        << pad(meanStd(collect(runs, false, [](const RunRecord& r) { return double(r.result.local_planner_calls); }), 0), w)
        << pad(meanStd(collect(runs, false, [](const RunRecord& r) { return double(r.result.distance_queries); }), 0), w)
        << pad(meanStd(collect(runs, false, [](const RunRecord& r) { return double(r.result.milestones); }), 0), w)
        << pad(meanStd(collect(runs, false, [](const RunRecord& r) { return r.time_ms; }), 1), w)
        << pad(meanStd(collect(runs, true, [](const RunRecord& r) { return r.path_length; }), 3), w)
        << (options.simplify ? pad(meanStd(collect(runs, true, [](const RunRecord& r) { return r.raw_length; }), 3), w) : "")
        << meanStd(collect(runs, true, [](const RunRecord& r) { return r.min_clearance; }), 4) << "\n";
  }
  if (sharedBuild(scenario, options)) {
    out << "\n" << scenario.queries.size() << " queries per run, one build per run: queries solved, build time "
        << "(ms, median over runs), time per query (median and mean over all queries: a roadmap's first "
        << "queries may grow it), total time per run (build + all queries, mean over runs)\n";
    out << std::left << std::setw(17) << "planner" << std::setw(14) << "solved" << std::setw(12) << "build"
        << std::setw(14) << "query median" << std::setw(12) << "query mean" << "total per run\n";
    for (const auto& runs : results) {
      const std::vector<double> builds = buildTimes(runs);
      std::vector<double> per_query, totals(options.runs, 0.0);
      for (size_t i = 0; i < runs.runs.size(); ++i) {
        const RunRecord& r = runs.runs[i];
        per_query.push_back(r.time_ms - r.build_ms);
        totals[i / scenario.queries.size()] += r.time_ms;
      }
      std::ostringstream solved, b, q, m, t;
      solved << runs.solved() << "/" << runs.runs.size();
      b << std::fixed << std::setprecision(1) << statsOf(builds).median;
      q << std::fixed << std::setprecision(2) << statsOf(per_query).median;
      m << std::fixed << std::setprecision(2) << statsOf(per_query).mean;
      t << std::fixed << std::setprecision(1) << statsOf(totals).mean;
      out << std::left << std::setw(17) << runs.planner << std::setw(14) << solved.str() << std::setw(12) << b.str()
          << std::setw(14) << q.str() << std::setw(12) << m.str() << t.str() << "\n";
    }
  }
  out << std::right;
}

void writeJson(const std::string& file, const cspace::Scenario& scenario, const DriverOptions& options,
               const std::vector<PlannerRuns>& results, const Provenance& provenance) {
  std::ostringstream o;
  o << "{ \"version\": " << jsonString(provenance.version) << ", \"revision\": " << jsonString(provenance.revision)
    << ", \"started\": " << jsonString(provenance.started) << ", \"host\": " << jsonString(provenance.host)
    << ", \"cpu\": " << jsonString(provenance.cpu) << ", \"simd\": " << jsonString(provenance.simd) << ",\n  "
    << "\"scenario\": " << jsonString(scenario.name) << ", \"file\": " << jsonString(scenario.path)
    << ", \"scenario_hash\": " << jsonString(scenario.content_hash)
    << ", \"dof\": " << scenario.robot->dof() << ", \"runs\": " << options.runs
    << ", \"queries\": " << scenario.queries.size() << ", \"seed\": " << options.seed
    << ", \"threads\": " << options.threads << ", \"time_limit\": " << options.time_limit
    << ", \"simplified\": " << (options.simplify ? "true" : "false")
    << ", \"simplifier\": \"" << (!options.simplify ? "none" : options.simplify_svm ? "svpp" : "shortcut") << "\""
    << ", \"checker\": " << jsonString(options.checker) << ", \"random_queries\": " << options.queries
    << ", \"overrides\": " << overridesJson(options) << ",\n  \"results\": [\n";
  for (size_t p = 0; p < results.size(); ++p) {
    const auto& runs = results[p];
    const double n = static_cast<double>(runs.runs.size());
    auto field = [&](auto f) { return jsonStats(collect(runs, false, f)); };
    auto solved_field = [&](auto f) { return jsonStats(collect(runs, true, f)); };
    o << "    { \"planner\": " << jsonString(runs.planner) << ", \"solved\": " << runs.solved()
      << ", \"success_rate\": " << runs.solved() / n << ", \"certified\": " << runs.certified()
      << ",\n      \"parameters\": {";
    for (auto it = runs.parameters.begin(); it != runs.parameters.end(); ++it)
      o << (it == runs.parameters.begin() ? "" : ", ") << jsonString(it->first) << ": " << jsonString(it->second);
    o << "}"
      << ",\n      \"collision_checks\": " << field([](const RunRecord& r) { return double(r.result.collision_checks); })
      << ",\n      \"local_planner_calls\": " << field([](const RunRecord& r) { return double(r.result.local_planner_calls); })
      << ",\n      \"distance_queries\": " << field([](const RunRecord& r) { return double(r.result.distance_queries); })
      << ",\n      \"certified_segments\": " << field([](const RunRecord& r) { return double(r.result.certified_segments); })
      << ",\n      \"build_ms\": " << jsonStats(statsOf(buildTimes(runs)))
      << ",\n      \"query_ms\": " << field([](const RunRecord& r) { return r.time_ms - r.build_ms; })
      << ",\n      \"repaired_stretches\": " << field([](const RunRecord& r) { return double(r.result.repaired_stretches); })
      << ",\n      \"exact_checks\": " << field([](const RunRecord& r) { return double(r.result.exact_checks); })
      << ",\n      \"milestones\": " << field([](const RunRecord& r) { return double(r.result.milestones); })
      << ",\n      \"roadmap_edges\": " << field([](const RunRecord& r) { return double(r.result.roadmap_edges); })
      << ",\n      \"support_vectors\": " << field([](const RunRecord& r) { return double(r.result.support_vectors); })
      << ",\n      \"time_ms\": " << field([](const RunRecord& r) { return r.time_ms; })
      << ",\n      \"phase_ms\": {\"sampling\": " << field([](const RunRecord& r) { return r.result.times.sampling_ms; })
      << ", \"training\": " << field([](const RunRecord& r) { return r.result.times.training_ms; })
      << ", \"milestones\": " << field([](const RunRecord& r) { return r.result.times.milestones_ms; })
      << ", \"roadmap\": " << field([](const RunRecord& r) { return r.result.times.roadmap_ms; })
      << ", \"query\": " << field([](const RunRecord& r) { return r.result.times.query_ms; })
      << ", \"certify\": " << field([](const RunRecord& r) { return r.result.times.certify_ms; })
      << ", \"simplify\": " << field([](const RunRecord& r) { return r.simplify_ms; }) << "}"
      << ",\n      \"path_length\": " << solved_field([](const RunRecord& r) { return r.path_length; })
      << ",\n      \"raw_path_length\": " << solved_field([](const RunRecord& r) { return r.raw_length; })
      << ",\n      \"smoothness\": " << solved_field([](const RunRecord& r) { return r.smoothness; })
      << ",\n      \"min_clearance\": " << solved_field([](const RunRecord& r) { return r.min_clearance; })
      << ",\n      \"statuses\": [";
    for (size_t r = 0; r < runs.runs.size(); ++r)
      o << (r ? ", " : "") << "\"" << planners::planStatusName(runs.runs[r].result.status) << "\"";
    o << "],\n      \"records\": [";  // every run, so shards of a sweep merge exactly (run_records.hpp)
    for (size_t r = 0; r < runs.runs.size(); ++r) o << (r ? ",\n        " : "\n        ") << runRecordJson(runs.runs[r]);
    o << "] }" << (p + 1 < results.size() ? "," : "") << "\n";
  }
  o << "  ]\n}\n";
  writeFileAtomically(file, o.str());
}

void writePathsJson(const std::string& file, const cspace::Scenario& scenario,
                    const std::vector<PlannerRuns>& results) {
  std::ostringstream o;
  o << std::setprecision(17) << "{ \"scenario\": " << jsonString(scenario.name) << ", \"dof\": "
    << scenario.robot->dof() << ",\n  \"runs\": [\n";
  bool first = true;
  for (const auto& runs : results)
    for (const auto& r : runs.runs) {
      o << (first ? "" : ",\n") << "    { \"planner\": " << jsonString(runs.planner) << ", \"seed\": " << r.seed
        << ", \"query\": " << r.query << ", \"status\": \"" << planners::planStatusName(r.result.status)
        << "\", \"certified\": " << (r.result.certified ? "true" : "false") << ", \"path\": [";
      for (size_t i = 0; i < r.result.path.size() && r.result.solved(); ++i) {
        o << (i ? ", " : "") << "[";
        for (int d = 0; d < r.result.path[i].size(); ++d) o << (d ? ", " : "") << r.result.path[i][d];
        o << "]";
      }
      o << "] }";
      first = false;
    }
  o << "\n  ]\n}\n";
  writeFileAtomically(file, o.str());
}

void writePathMatrices(const std::string& dir, const cspace::Scenario& scenario,
                       const std::vector<PlannerRuns>& results, std::ostream& log) {
  for (const auto& runs : results)
    for (const auto& r : runs.runs) {
      if (!r.result.solved()) continue;
      std::ostringstream name, text;
      name << scenario.name << "_" << runs.planner << "_seed" << r.seed;
      if (scenario.queries.size() > 1) name << "_query" << r.query;
      text << std::setprecision(17);
      for (const auto& q : r.result.path) {
        for (int d = 0; d < q.size(); ++d) text << (d ? " " : "") << q[d];
        text << "\n";
      }
      const std::string file = dir + "/" + safeFileName(name.str()) + ".txt";
      writeFileAtomically(file, text.str());
      log << "  wrote " << file << "\n";
    }
}

}  // namespace svmp::experiments
