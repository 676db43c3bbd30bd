// svmp-fastron: the experiments of Das & Yip 2019 (Fastron with the FK kernel) on a scenario's robot
// (docs/fastron.md). --experiment collision: sec. IV-A (Table I, Figs 4 and 7); planning: sec. IV-B
// (Fig 6); picture: Fig 1 (a 3-DoF arm's C-space slice, SVG); all: every one. Prints tables, writes
// JSON (whole or not at all). Bad input: one error naming the flag or field, exit status 2.
#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <map>
#include <sstream>

#include "bench/experiments/atomic_file.hpp"
#include "bench/experiments/driver_options.hpp"
#include "bench/experiments/fastron/collision_experiment.hpp"
#include "bench/experiments/fastron/cspace_picture.hpp"
#include "bench/experiments/fastron/planning_experiment.hpp"
#include "bench/experiments/output_text.hpp"
#include "planners/planner_registry.hpp"

namespace {

using namespace svmp;

const char* kUsage =
    "usage: svmp-fastron --scenario FILE [--experiment collision|planning|picture|all] [--trials N]\n"
    "                    [--moves M] [--test-samples N] [--obstacle-trials N] [--plans-per-move N]\n"
    "                    [--planners LIST] [--time-limit SEC] [--seed S] [--json FILE] [--svg DIR]\n"
    "                    [--set fastron-fk.KEY=VALUE|fastron-rbf.KEY=VALUE ...]\n"
    "  collision, planning: the scenario's robot among a moving box (docs/fastron.md); picture: the\n"
    "  paper's Fig 1, its own 3-DoF arm and obstacles (the scenario's parameters only)\n";

struct Flags {
  std::string scenario, experiment = "all", json, svg;
  int trials = 50, moves = 30, test_samples = 2000, obstacle_trials = 3, plans_per_move = 10;
  double time_limit = 10;
  bool help = false;
  std::uint64_t seed = 1;
  std::string planners;
  std::map<std::string, cspace::ParameterSet> params;  // fastron-fk, fastron-rbf
};

long parseInt(const std::string& flag, const std::string& v, long lo, long hi) {
  char* end = nullptr;
  errno = 0;
  const long x = std::strtol(v.c_str(), &end, 10);
  if (v.empty() || *end || errno || x < lo || x > hi)
    throw cspace::ScenarioError("flag " + flag + ": '" + v + "' is not an integer in [" + std::to_string(lo) + ", " +
                                std::to_string(hi) + "]");
  return x;
}

double parseDouble(const std::string& flag, const std::string& v, double lo, double hi) {
  char* end = nullptr;
  const double x = std::strtod(v.c_str(), &end);
  if (v.empty() || *end || !(x >= lo && x <= hi))
    throw cspace::ScenarioError("flag " + flag + ": '" + v + "' is not a number in [" + std::to_string(lo) + ", " +
                                std::to_string(hi) + "]");
  return x;
}

Flags parse(int argc, char** argv) {
  Flags f;
  for (const char* name : {"fastron-fk", "fastron-rbf"})
    f.params[name] = cspace::ParameterSet("flag --set", std::string(name) + ".", {});
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    if (flag == "--help" || flag == "-h") {
      f.help = true;
      return f;
    }
    if (i + 1 >= argc) throw cspace::ScenarioError("flag " + flag + " needs a value (or is unknown)");
    const std::string v = argv[++i];
    if (flag == "--scenario") f.scenario = v;
    else if (flag == "--experiment") {
      if (v != "collision" && v != "planning" && v != "picture" && v != "all")
        throw cspace::ScenarioError("flag --experiment: '" + v + "' is not collision, planning, picture or all");
      f.experiment = v;
    } else if (flag == "--trials") f.trials = static_cast<int>(parseInt(flag, v, 1, 100000));
    else if (flag == "--moves") f.moves = static_cast<int>(parseInt(flag, v, 0, 100000));
    else if (flag == "--test-samples") f.test_samples = static_cast<int>(parseInt(flag, v, 64, 10000000));
    else if (flag == "--obstacle-trials") f.obstacle_trials = static_cast<int>(parseInt(flag, v, 0, 1000));
    else if (flag == "--plans-per-move") f.plans_per_move = static_cast<int>(parseInt(flag, v, 1, 100000));
    else if (flag == "--time-limit") f.time_limit = parseDouble(flag, v, 1e-3, 1e6);
    else if (flag == "--seed") f.seed = static_cast<std::uint64_t>(parseInt(flag, v, 0, 1L << 62));
    else if (flag == "--planners") {
      if (v.empty()) throw cspace::ScenarioError("flag --planners: empty list");
      f.planners = v;
    }
    else if (flag == "--json") f.json = v;
    else if (flag == "--svg") f.svg = v;
    else if (flag == "--set") {
      const auto dot = v.find('.'), eq = v.find('=');
      if (dot == std::string::npos || eq == std::string::npos || eq < dot)
        throw cspace::ScenarioError("flag --set: '" + v + "' is not CHECKER.KEY=VALUE");
      const std::string checker = v.substr(0, dot);
      if (!f.params.count(checker))
        throw cspace::ScenarioError("flag --set " + v + ": unknown checker '" + checker + "' (fastron-fk, fastron-rbf)");
      const std::string key = v.substr(dot + 1, eq - dot - 1);
      if (f.params[checker].has(key))  // only flags fill these: the last value would silently win
        throw cspace::ScenarioError("flag --set " + v + ": " + checker + "." + key + " is already set");
      f.params[checker].set(key, v.substr(eq + 1), "flag --set " + v);
    } else {
      throw cspace::ScenarioError("unknown flag " + flag);
    }
  }
  if (f.scenario.empty()) throw cspace::ScenarioError("flag --scenario is required");
  return f;
}

}  // namespace

int main(int argc, char** argv) {
  Flags flags;
  try {
    flags = parse(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "svmp-fastron: " << e.what() << "\n" << kUsage;
    return 2;
  }
  if (flags.help) {
    std::cout << kUsage;
    return 0;
  }
  try {
    experiments::checkDistinct({{"--scenario", flags.scenario}, {"--json", flags.json}}, {{"--svg", flags.svg}});
    const cspace::Scenario scenario = cspace::loadScenario(flags.scenario);
    // The scenario's fastron-fk / fastron-rbf sections, then --set over them (as svmp-plan --checker).
    std::map<std::string, cspace::ParameterSet> params;
    for (const auto& [name, set] : flags.params) {
      params[name] = scenario.paramsFor(name);
      for (const auto& [key, value] : set.values())
        params[name].set(key, value, "flag --set " + name + "." + key + "=" + value);
    }
    const auto fk = cspace::FastronCheckerOptions::fromParameters("fastron-fk", params["fastron-fk"]);
    const auto rbf = cspace::FastronCheckerOptions::fromParameters("fastron-rbf", params["fastron-rbf"]);
    for (const auto& [name, p] : params) p.requireAllUsed();
    const bool plans = flags.experiment == "all" || flags.experiment == "planning";
    if (!flags.planners.empty() && !plans)
      throw cspace::ScenarioError("flag --planners: only --experiment planning (or all) plans; this run is '" +
                                  flags.experiment + "'");
    // Before the experiments, which take minutes: a bad name must not wait for them.
    const auto planner_list = flags.planners.empty() ? std::vector<std::string>() : experiments::parsePlannerList(flags.planners);
    const auto known = planners::plannerNames();
    for (const auto& name : planner_list)
      if (std::find(known.begin(), known.end(), name) == known.end())
        throw cspace::ScenarioError("flag --planners: " + planners::unknownPlanner(name));
    if (!flags.json.empty()) experiments::checkWritable("--json", flags.json);
    if (!flags.svg.empty()) experiments::makeDirectory("--svg", flags.svg);
    const bool all = flags.experiment == "all";
    std::ostringstream json;
    json << "{\"scenario\": " << experiments::jsonString(scenario.name) << ", \"seed\": " << flags.seed;
    if (all || flags.experiment == "collision") {
      experiments::fastron::CollisionExperimentOptions o;
      o.trials = flags.trials, o.moves = flags.moves, o.test_samples = flags.test_samples, o.seed = flags.seed;
      o.obstacle_trials = flags.obstacle_trials, o.fk = fk, o.rbf = rbf;
      if (o.obstacle_trials == 0) o.obstacle_counts.clear();
      const auto r = experiments::fastron::runCollisionExperiment(scenario, o, std::cerr);
      experiments::fastron::printCollisionTables(r, std::cout);
      json << ", \"collision\": " << experiments::fastron::collisionJson(r);
    }
    if (all || flags.experiment == "planning") {
      experiments::fastron::PlanningExperimentOptions o;
      o.trials = flags.trials, o.moves = flags.moves, o.plans_per_move = flags.plans_per_move, o.seed = flags.seed;
      o.time_limit = flags.time_limit, o.fk = fk, o.rbf = rbf;
      if (!planner_list.empty()) o.planners = planner_list;
      const auto r = experiments::fastron::runPlanningExperiment(scenario, o, std::cerr);
      experiments::fastron::printPlanningTable(r, std::cout);
      json << ", \"planning\": " << experiments::fastron::planningJson(r);
    }
    if (all || flags.experiment == "picture") {
      const std::string dir = flags.svg.empty() ? "." : flags.svg;
      const auto r = experiments::fastron::drawCspacePicture(dir, flags.seed, fk, rbf);
      std::cout << "\nFig 1: " << r.file << " (ground truth " << r.grid << "x" << r.grid << ", fastron-fk "
                << r.fk_support << " support points, " << r.fk_accuracy * 100 << "% on the grid; fastron-rbf "
                << r.rbf_support << ", " << r.rbf_accuracy * 100 << "%)\n";
      json << ", \"picture\": {\"file\": " << experiments::jsonString(r.file) << ", \"fk_support\": " << r.fk_support
           << ", \"rbf_support\": " << r.rbf_support << ", \"fk_accuracy\": " << r.fk_accuracy
           << ", \"rbf_accuracy\": " << r.rbf_accuracy << "}";
    }
    json << "}\n";
    if (!flags.json.empty()) experiments::writeFileAtomically(flags.json, json.str());
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "svmp-fastron: " << e.what() << "\n";
    return 2;
  }
}
