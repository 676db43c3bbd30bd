#include "bench/experiments/driver_options.hpp"

#include <algorithm>
#include <cstdlib>
#include <sstream>
#include <stdexcept>

namespace svmp::experiments {

long parseLong(const std::string& flag, const std::string& value, long min, long max) {
  char* end = nullptr;
  const long v = std::strtol(value.c_str(), &end, 10);
  if (value.empty() || *end != '\0' || v < min || v > max)
    throw std::invalid_argument("flag " + flag + ": expected an integer in [" + std::to_string(min) +
                                ", " + std::to_string(max) + "], got '" + value + "'");
  return v;
}

double parseDouble(const std::string& flag, const std::string& value, double min, double max) {
  char* end = nullptr;
  const double v = std::strtod(value.c_str(), &end);
  if (value.empty() || *end != '\0' || !(v >= min && v <= max))
    throw std::invalid_argument("flag " + flag + ": expected a number in [" + std::to_string(min) + ", " +
                                std::to_string(max) + "], got '" + value + "'");
  return v;
}

bool isCheckerName(const std::string& name) { return name == "fcl" || name == "fastron-fk" || name == "fastron-rbf"; }

const char* driverUsage() {
  return "usage: svmp-plan --scenario FILE [--planners LIST] [--runs N] [--seed S] [--threads T]\n"
         "                 [--json FILE] [--svg DIR] [--paths FILE] [--path-dir DIR] [--simplify [svpp]]\n"
         "                 [--set PLANNER.KEY=VALUE ...] [--time-limit SEC] [--checker NAME] [--queries N]\n"
         "                 [--ompl-log FILE] [--check] [--version]\n"
         "  --planners  comma-separated (default svmp,prm): svmp, prm, local, svpp, ompl-prm, ompl-lazyprm,\n"
         "              ompl-rrtconnect, ompl-rrt, ompl-sbl, ompl-rrtstar, ompl-fmt, ompl-informedrrtstar\n"
         "  --runs      runs per planner, seeds S, S+1, ... (default 1); --seed S: the first (default 1)\n"
         "  --threads   OpenMP threads of each run (default 1); the same seed and threads give the same result,\n"
         "              but for runs a time limit ends (OMPL's: 10 s without --time-limit) and ompl-prm, which\n"
         "              OMPL grows by wall time\n"
         "  --set       a planner parameter over the file's (planners.PLANNER.KEY); the planner must be in\n"
         "              --planners, fastron-*.KEY needs that --checker, svpp.KEY goes with --simplify svpp\n"
         "  --json      the table's statistics, every run's record, each planner's parameters (as set,\n"
         "              defaulted or derived) and what produced them (version, revision, host, CPU)\n"
         "  --svg       SVG pictures of each planner's first run: the C-space (2 dof), the workspace (planar\n"
         "              robots), svpp's patterns\n"
         "  --time-limit  seconds per run (with several queries: for the build and for each query); a planner\n"
         "              that reaches it reports status timeout\n"
         "  --paths     JSON of every run's certified path (waypoints); --path-dir: one OMPL matrix\n"
         "              text file per solved run (one configuration a line)\n"
         "  --simplify  shortcut and reduce every solved path, each new segment certified; --simplify svpp:\n"
         "              follow an SVM separating the obstacles by the side of the path instead (point robots)\n"
         "  --queries   N random valid start-goal pairs (from --seed) instead of the file's queries; roadmap\n"
         "              planners build once per run and answer all of them\n"
         "  --checker   fcl (default), fastron-fk or fastron-rbf: plan on a learned proxy checker; every\n"
         "              path is verified on FCL and its invalid stretches replanned (verify and repair)\n"
         "  --ompl-log  every run of every planner in OMPL's benchmark log format: ompl_benchmark_statistics\n"
         "              -d DB FILE makes the database Planner Arena reads\n"
         "  --check     print the scenario's summary, validate planners and --set, verify the witness, warn\n"
         "              of obstacles thinner than one resolution step, list each planner's parameters (value,\n"
         "              set / default / derived, range)\n"
         "  --version   the version, the git revision it was built from and the SVM loops' instruction set\n"
         "       svmp-plan --merge SHARD.json... [--json FILE] [--scenario FILE]\n"
         "  --merge     merge the --json files of shards of one run (seed ranges of scripts/sweep) into that\n"
         "              run's table and JSON; the scenario is the shards' \"file\" unless --scenario is given\n";
}

std::vector<std::string> parsePlannerList(const std::string& text) {
  std::vector<std::string> names;
  std::stringstream list(text);
  for (std::string name; std::getline(list, name, ',');) {
    if (std::find(names.begin(), names.end(), name) != names.end())
      throw std::invalid_argument("flag --planners: '" + name + "' listed twice");
    if (name.empty()) throw std::invalid_argument("flag --planners: an empty name in '" + text + "'");
    names.push_back(name);
  }
  if (names.empty() || text.back() == ',') throw std::invalid_argument("flag --planners: an empty name in '" + text + "'");
  return names;
}

void addOverride(DriverOptions& options, const std::string& key, const std::string& value) {
  for (const auto& [given, was] : options.overrides)
    if (given == key) throw std::invalid_argument(key + " is already set to '" + was + "'");
  options.overrides.emplace_back(key, value);
}

DriverOptions parseDriverOptions(int argc, const char* const* argv) {
  DriverOptions o;
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw std::invalid_argument("flag " + flag + ": missing value");
      return argv[++i];
    };
    if (flag == "--scenario") o.scenario = value();
    else if (flag == "--planners") o.planners = parsePlannerList(value());
    else if (flag == "--runs") o.runs = static_cast<int>(parseLong(flag, value(), 1, 100000));
    else if (flag == "--seed") o.seed = static_cast<unsigned long>(parseLong(flag, value(), 0, kMaxSeed));
    else if (flag == "--threads") o.threads = static_cast<int>(parseLong(flag, value(), 1, kMaxThreads));
    else if (flag == "--time-limit") o.time_limit = parseDouble(flag, value(), 1e-6, 1e7);
    else if (flag == "--queries") o.queries = static_cast<int>(parseLong(flag, value(), 1, 100000));
    else if (flag == "--checker") {
      o.checker = value();
      if (!isCheckerName(o.checker))
        throw std::invalid_argument("flag --checker: '" + o.checker + "' is not fcl, fastron-fk or fastron-rbf");
    }
    else if (flag == "--json") o.json_path = value();
    else if (flag == "--svg") o.svg_dir = value();
    else if (flag == "--paths") o.paths_json = value();
    else if (flag == "--path-dir") o.paths_dir = value();
    else if (flag == "--ompl-log") o.ompl_log = value();
    else if (flag == "--simplify") {
      o.simplify = true;
      if (i + 1 < argc && (std::string(argv[i + 1]) == "svpp" || std::string(argv[i + 1]) == "shortcut"))
        o.simplify_svm = std::string(argv[++i]) == "svpp";
    }
    else if (flag == "--set") {
      const std::string kv = value();
      const size_t eq = kv.find('='), dot = kv.find('.');
      if (eq == std::string::npos || dot == std::string::npos || dot > eq || dot == 0 || eq == dot + 1)
        throw std::invalid_argument("flag --set: expected PLANNER.KEY=VALUE, got '" + kv + "'");
      try {
        addOverride(o, kv.substr(0, eq), kv.substr(eq + 1));
      } catch (const std::invalid_argument& e) {
        throw std::invalid_argument("flag --set " + kv + ": " + e.what());
      }
    } else if (flag == "--merge") {
      while (i + 1 < argc && std::string(argv[i + 1]).rfind("--", 0) != 0) o.merge_files.push_back(argv[++i]);
      if (o.merge_files.empty()) throw std::invalid_argument("flag --merge: expected shard JSON files");
    } else if (flag == "--check") o.check = true;
    else if (flag == "--help" || flag == "-h") o.help = true;
    else if (flag == "--version") o.version = true;
    else throw std::invalid_argument("unknown flag '" + flag + "'");
  }
  if (!o.merge_files.empty())
    for (int i = 1; i < argc; ++i) {
      const std::string flag = argv[i];
      if (flag.rfind("--", 0) == 0 && flag != "--merge" && flag != "--json" && flag != "--scenario")
        throw std::invalid_argument("flag " + flag + ": not used with --merge (the shards' JSON says how they ran)");
    }
  if (!o.help && !o.version && o.scenario.empty() && o.merge_files.empty())
    throw std::invalid_argument("flag --scenario is required");
  for (const auto& [flag, path] : {std::pair{"--json", &o.json_path}, std::pair{"--paths", &o.paths_json},
                                   std::pair{"--svg", &o.svg_dir}, std::pair{"--path-dir", &o.paths_dir},
                                   std::pair{"--ompl-log", &o.ompl_log}})
    if (path->empty() && std::find(argv, argv + argc, std::string(flag)) != argv + argc)
      throw std::invalid_argument(std::string("flag ") + flag + ": empty path");
  return o;
}

}  // namespace svmp::experiments
