// svmp-plan: the experiment driver (docs/architecture.md, "The driver"). Loads a scenario, runs each
// planner N times with seeds S, S+1, ..., prints the thesis-style table and writes JSON and pictures;
// --merge joins the JSON of a sweep's shards (scripts/sweep) into the single run's table and JSON.
// Bad input: one clear error, exit status 2.
#include <chrono>
#include <iostream>
#include <new>
#include <sstream>

#include "bench/experiments/atomic_file.hpp"
#include "bench/experiments/driver_options.hpp"
#include "bench/experiments/experiment.hpp"
#include "bench/experiments/ompl_log.hpp"
#include "bench/experiments/run_records.hpp"
#include "bench/experiments/scenario_check.hpp"
#include "cspace/scenario/scenario.hpp"

int main(int argc, char** argv) {
  using namespace svmp;
  experiments::DriverOptions options;
  try {
    options = experiments::parseDriverOptions(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "svmp-plan: " << e.what() << "\n" << experiments::driverUsage();
    return 2;
  }
  if (options.help) {
    std::cout << experiments::driverUsage();
    return 0;
  }
  if (options.version) {
    const experiments::Provenance p = experiments::Provenance::now();
    std::cout << "svmp-plan " << p.version << " (revision " << p.revision << ", SVM loops " << p.simd << ")\n";
    return 0;
  }
  try {
    if (!options.merge_files.empty()) {
      if (!options.json_path.empty()) experiments::checkWritable("--json", options.json_path);
      for (const auto& shard : options.merge_files)  // a shard given twice is the merge's to refuse
        experiments::checkDistinct({{"--merge", shard}, {"--scenario", options.scenario}, {"--json", options.json_path}});
      const auto merged = experiments::mergeShards(options.merge_files, options.scenario);
      experiments::printTable(merged.scenario, merged.options, merged.results, std::cout);
      if (!options.json_path.empty())
        experiments::writeJson(options.json_path, merged.scenario, merged.options, merged.results, merged.provenance);
      return 0;
    }
    experiments::checkDistinct({{"--scenario", options.scenario}, {"--json", options.json_path},
                                {"--paths", options.paths_json}, {"--ompl-log", options.ompl_log}},
                               {{"--svg", options.svg_dir}, {"--path-dir", options.paths_dir}});
    cspace::Scenario scenario = cspace::loadScenario(options.scenario);
    if (options.queries > 0) scenario.queries = experiments::randomQueries(scenario, options.queries, options.seed);
    if (options.check) {
      std::ostringstream parameters;
      experiments::validatePlanners(scenario, options, &parameters);
      const bool ok = experiments::printScenarioCheck(scenario, std::cout);
      std::cout << parameters.str();
      return ok ? 0 : 1;
    }
    experiments::requireValidConfigurations(scenario);
    for (const auto& [flag, dir] : {std::pair{"--svg", options.svg_dir}, std::pair{"--path-dir", options.paths_dir}})
      if (!dir.empty()) experiments::makeDirectory(flag, dir);
    if (!options.json_path.empty()) experiments::checkWritable("--json", options.json_path);
    if (!options.paths_json.empty()) experiments::checkWritable("--paths", options.paths_json);
    if (!options.ompl_log.empty()) {
#ifdef SVMP_WITH_OMPL
      experiments::checkWritable("--ompl-log", options.ompl_log);
#else
      std::cerr << "svmp-plan: flag --ompl-log " << options.ompl_log << ": this build has no OMPL (SVMP_WITH_OMPL=OFF)\n";
      return 2;
#endif
    }
    std::cerr << "svmp-plan: " << scenario.name << ": running " << options.planners.size() << " planner(s), "
              << options.runs << " run(s) each\n";
    const experiments::Provenance provenance = experiments::Provenance::now();
#ifdef SVMP_WITH_OMPL
    experiments::ExperimentTiming timing{provenance.started, 0};
#endif
    [[maybe_unused]] const auto t0 = std::chrono::steady_clock::now();
    const auto results = experiments::runExperiment(scenario, options, std::cerr);
#ifdef SVMP_WITH_OMPL
    timing.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
#endif
    experiments::printTable(scenario, options, results, std::cout);
    if (!options.json_path.empty())
      experiments::writeJson(options.json_path, scenario, options, results, provenance);
    if (!options.paths_json.empty()) experiments::writePathsJson(options.paths_json, scenario, results);
    if (!options.paths_dir.empty()) experiments::writePathMatrices(options.paths_dir, scenario, results, std::cerr);
#ifdef SVMP_WITH_OMPL
    if (!options.ompl_log.empty())
      experiments::writeOmplLog(options.ompl_log, scenario, options, results, timing);
#endif
    return 0;
  } catch (const cspace::ScenarioError& e) {
    std::cerr << "svmp-plan: " << e.what() << "\n";
    return 2;
  } catch (const std::invalid_argument& e) {
    std::cerr << "svmp-plan: " << options.scenario << ": " << e.what() << "\n";
    return 2;
  } catch (const std::runtime_error& e) {
    std::cerr << "svmp-plan: " << e.what() << "\n";
    return 2;
  } catch (const std::length_error& e) {  // a segment the validator refuses to count (never "free")
    std::cerr << "svmp-plan: " << options.scenario << ": " << e.what() << "\n";
    return 2;
  } catch (const std::bad_alloc&) {  // the input asked for more memory than the machine has
    std::cerr << "svmp-plan: " << options.scenario << ": out of memory (the scenario or the flags ask for more "
              << "than this machine can hold; no output was written)\n";
    return 2;
  }
}
