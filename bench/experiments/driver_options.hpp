#pragma once
// Command line of svmp-plan (docs/architecture.md, "The driver").
#include <string>
#include <utility>
#include <vector>

namespace svmp::experiments {

// Bounds of --seed and --threads; the Python module checks its arguments against the same.
inline constexpr long kMaxSeed = 1L << 62;
inline constexpr int kMaxThreads = 256;  // 1,024 could not all be created under a 6 GB address limit
// fcl, fastron-fk or fastron-rbf (--checker).
bool isCheckerName(const std::string& name);

struct DriverOptions {
  std::string scenario;
  std::vector<std::string> planners = {"svmp", "prm"};
  int runs = 1;
  unsigned long seed = 1;
  int threads = 1;
  int queries = 0;  // --queries N: N seeded random valid start-goal pairs instead of the file's queries
  std::string checker = "fcl";  // --checker: fcl, fastron-fk or fastron-rbf (learned proxy, verify and repair)
  double time_limit = 0;  // seconds per run; with several queries, for the build and for each query; 0: none
  std::string json_path;
  std::string svg_dir;
  std::string paths_json;  // --paths: every run's certified waypoints
  std::string paths_dir;   // --path-dir: one OMPL matrix text file per solved run
  std::string ompl_log;    // --ompl-log: every run in OMPL's benchmark log format (Planner Arena)
  bool simplify = false;   // --simplify: shortcut and reduce every solved path (certified)
  bool simplify_svm = false;  // --simplify svpp: SVM smoothing instead (Miura 2006 sec. V-A; point robots)
  std::vector<std::pair<std::string, std::string>> overrides;  // ("svmp.sigma", "0.3")
  bool check = false;
  bool help = false;
  bool version = false;  // --version: the version and git revision this binary was built from
  // --merge FILE...: no runs; merge shard JSONs of one sweep into the single run's table and --json
  // (bench/experiments/run_records.hpp). Only --json and --scenario go with it.
  std::vector<std::string> merge_files;
};

// A comma-separated --planners value; throws std::invalid_argument for an empty list, an empty name
// (svmp,,prm) or a name listed twice.
std::vector<std::string> parsePlannerList(const std::string& text);
// Adds PLANNER.KEY = VALUE to `options.overrides`; throws std::invalid_argument when the key is
// already set (the last value would silently win).
void addOverride(DriverOptions& options, const std::string& key, const std::string& value);

// A flag's integer or number within [min, max]; throws std::invalid_argument naming the flag and value.
long parseLong(const std::string& flag, const std::string& value, long min, long max);
double parseDouble(const std::string& flag, const std::string& value, double min, double max);

// Throws std::invalid_argument naming the flag and the value.
DriverOptions parseDriverOptions(int argc, const char* const* argv);
const char* driverUsage();

}  // namespace svmp::experiments
