// svmp-ompl-benchmark: our planners beside OMPL's in OMPL's own benchmarking (OMPL 1.5,
// ompl::tools::Benchmark; Moll, Sucan, Kavraki, "Benchmarking Motion Planning Algorithms", IEEE RAM
// 2015). Loads a scenario, plans in an ompl::geometric::SimpleSetup on our FCL checker and validator
// (planners/ompl/scenario_setup.hpp), runs each planner --runs times under --time-limit and writes
// OMPL's log (whole or not at all), which ompl_benchmark_statistics turns into Planner Arena's database.
// Our planners (svmp, prm, local, svpp: planners/ompl/svm_planners.hpp) take the scenario's parameters;
// OMPL's eight (PRM, LazyPRM, RRTConnect, RRT, SBL, RRTstar, FMT, InformedRRTstar, or by svmp-plan's
// names ompl-prm, ...) OMPL's defaults; --set PLANNER.KEY=VALUE sets either through OMPL's ParamSet,
// as Planner Arena lists them. Every run also records "collision checks"
// (configurations our checker tested during the run, whoever asked), "certified" (its path proven
// by our certifier, OMPL's planners' too) and, for ours, our counters
// (bench/experiments/ompl_log.hpp counterProperties).
// Bad input: one error naming the flag or file and value, exit status 2.
#include <ompl/geometric/planners/fmt/FMT.h>
#include <ompl/geometric/planners/prm/LazyPRM.h>
#include <ompl/geometric/planners/prm/PRM.h>
#include <ompl/geometric/planners/rrt/InformedRRTstar.h>
#include <ompl/geometric/planners/rrt/RRT.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/geometric/planners/rrt/RRTstar.h>
#include <ompl/geometric/planners/sbl/SBL.h>
#include <ompl/tools/benchmark/Benchmark.h>
#include <ompl/util/RandomNumbers.h>

#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <map>
#include <sstream>

#include "bench/experiments/atomic_file.hpp"
#include "bench/experiments/scenario_check.hpp"
#include "bench/experiments/driver_options.hpp"
#include "bench/experiments/ompl_log.hpp"
#include "cspace/scenario/scenario.hpp"
#include "planners/ompl/scenario_setup.hpp"
#include "planners/ompl/state_bridge.hpp"
#include "planners/ompl/svm_planners.hpp"

namespace {

namespace ob = ompl::base;
namespace og = ompl::geometric;
using namespace svmp;

const char* kUsage =
    "usage: svmp-ompl-benchmark --scenario FILE --log FILE [--planners LIST] [--runs N] [--time-limit SEC]\n"
    "                           [--seed S] [--threads T] [--query I] [--set PLANNER.KEY=VALUE ...]\n"
    "  --planners   comma-separated, default svmp,PRM,RRTConnect: ours (svmp, prm, local, svpp) and\n"
    "               OMPL's (PRM, LazyPRM, RRTConnect, RRT, SBL, RRTstar, FMT, InformedRRTstar, or as\n"
    "               svmp-plan names them: ompl-prm, ompl-lazyprm, ompl-rrtconnect, ...)\n"
    "  --set        a parameter of a planner of --planners, through OMPL's ParamSet (Planner Arena's\n"
    "               names; ours take the scenario's keys)\n"
    "  --runs       runs per planner (default 10); --time-limit seconds per run (default 10)\n"
    "  --seed       OMPL's random seed (ompl::RNG::setSeed), default 1; --query: the scenario's query (0)\n"
    "  --log        OMPL's benchmark log: ompl_benchmark_statistics -d DB FILE, then Planner Arena\n";

struct Flags {
  std::string scenario, log;
  std::vector<std::string> planners = {"svmp", "PRM", "RRTConnect"};
  std::vector<std::pair<std::string, std::string>> sets;  // ("PLANNER.KEY", "VALUE")
  int runs = 10, threads = 1, query = 0;
  double time_limit = 10;
  unsigned long seed = 1;
};

// OMPL's class name of a planner svmp-plan names ompl-*; any other name as it is.
std::string omplName(const std::string& name) {
  static const std::map<std::string, std::string> kOmpl = {
      {"ompl-prm", "PRM"}, {"ompl-lazyprm", "LazyPRM"}, {"ompl-rrtconnect", "RRTConnect"}, {"ompl-rrt", "RRT"},
      {"ompl-sbl", "SBL"}, {"ompl-rrtstar", "RRTstar"}, {"ompl-fmt", "FMT"}, {"ompl-informedrrtstar", "InformedRRTstar"}};
  const auto it = kOmpl.find(name);
  return it == kOmpl.end() ? name : it->second;
}

Flags parseFlags(int argc, char** argv) {
  Flags f;
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    if (flag == "--help" || flag == "-h") throw std::invalid_argument("");
    if (i + 1 >= argc) throw std::invalid_argument("flag " + flag + ": missing value");
    const std::string v = argv[++i];
    if (flag == "--scenario") f.scenario = v;
    else if (flag == "--log") f.log = v;
    else if (flag == "--runs") f.runs = static_cast<int>(experiments::parseLong(flag, v, 1, 100000));
    else if (flag == "--threads") f.threads = static_cast<int>(experiments::parseLong(flag, v, 1, experiments::kMaxThreads));
    else if (flag == "--query") f.query = static_cast<int>(experiments::parseLong(flag, v, 0, 100000));
    else if (flag == "--seed") f.seed = static_cast<unsigned long>(experiments::parseLong(flag, v, 1, experiments::kMaxSeed));
    else if (flag == "--time-limit") f.time_limit = experiments::parseDouble(flag, v, 1e-3, 1e6);
    else if (flag == "--planners") {
      f.planners.clear();
      for (const std::string& name : experiments::parsePlannerList(v)) f.planners.push_back(omplName(name));
      for (size_t p = 0; p < f.planners.size(); ++p)  // PRM and ompl-prm are one planner
        if (std::find(f.planners.begin(), f.planners.begin() + p, f.planners[p]) != f.planners.begin() + p)
          throw std::invalid_argument("flag --planners: '" + f.planners[p] + "' listed twice");
    }
    else if (flag == "--set") {
      const size_t dot = v.find('.'), eq = v.find('=');
      if (dot == std::string::npos || eq == std::string::npos || dot > eq)
        throw std::invalid_argument("flag --set " + v + ": expected PLANNER.KEY=VALUE");
      const std::string key = omplName(v.substr(0, dot)) + v.substr(dot, eq - dot);
      for (const auto& [given, was] : f.sets)
        if (given == key) throw std::invalid_argument("flag --set " + v + ": " + key + " is already set to '" + was + "'");
      f.sets.emplace_back(key, v.substr(eq + 1));
    }
    else throw std::invalid_argument("unknown flag '" + flag + "'");
  }
  if (f.scenario.empty()) throw std::invalid_argument("flag --scenario is required");
  if (f.log.empty()) throw std::invalid_argument("flag --log is required");
  for (const auto& [key, value] : f.sets)
    if (std::find(f.planners.begin(), f.planners.end(), key.substr(0, key.find('.'))) == f.planners.end())
      throw std::invalid_argument("flag --set " + key + "=" + value + ": planner '" + key.substr(0, key.find('.')) +
                                  "' is not among --planners");
  return f;
}

// OMPL's planners by their class names (omplName).
ob::PlannerPtr makeOmplPlanner(const std::string& name, const ob::SpaceInformationPtr& si) {
  if (name == "PRM") return std::make_shared<og::PRM>(si);
  if (name == "LazyPRM") return std::make_shared<og::LazyPRM>(si);
  if (name == "RRTConnect") return std::make_shared<og::RRTConnect>(si);
  if (name == "RRT") return std::make_shared<og::RRT>(si);
  if (name == "SBL") return std::make_shared<og::SBL>(si);
  if (name == "RRTstar") return std::make_shared<og::RRTstar>(si);
  if (name == "FMT") return std::make_shared<og::FMT>(si);
  if (name == "InformedRRTstar") return std::make_shared<og::InformedRRTstar>(si);
  return nullptr;
}

// The planner `name` with the --set values that name it.
ob::PlannerPtr makePlanner(const std::string& name, const ob::SpaceInformationPtr& si, const cspace::Scenario& s,
                           const std::vector<std::pair<std::string, std::string>>& sets) {
  ob::PlannerPtr planner = ompl_planners::makeSvmOmplPlanner(name, si, s.paramsFor(name));
  if (!planner) planner = makeOmplPlanner(name, si);
  if (!planner)
    throw std::invalid_argument("flag --planners: unknown planner '" + name +
                                "' (svmp, prm, local, svpp, PRM, LazyPRM, RRTConnect, RRT, SBL, RRTstar, FMT, "
                                "InformedRRTstar; or ompl-prm, ompl-lazyprm, ...)");
  for (const auto& [key, value] : sets) {
    if (key.substr(0, key.find('.')) != name) continue;
    const std::string param = key.substr(key.find('.') + 1);
    if (!planner->params().hasParam(param)) {
      std::vector<std::string> names;
      planner->params().getParamNames(names);
      std::string known;
      for (const std::string& n : names) known += (known.empty() ? "" : ", ") + n;
      throw std::invalid_argument("flag --set " + key + "=" + value + ": planner '" + name + "' has no parameter '" +
                                  param + "' (" + known + ")");
    }
    // A negative value where OMPL's suggested range starts at 0 or above (a count, a distance, a
    // factor): setParam takes it, and a count wraps (FMT.num_samples=-1 gave 4,294,967,295 samples
    // and ran past the time limit). The range is a suggestion, so values above it stay allowed.
    const std::string range = planner->params()[param].getRangeSuggestion();
    char* end = nullptr;
    const double lo = std::strtod(range.c_str(), &end), v = std::strtod(value.c_str(), nullptr);
    if (end != range.c_str() && *end == ':' && lo >= 0 && v < 0)
      throw std::invalid_argument("flag --set " + key + "=" + value + ": must not be negative (OMPL's range for " +
                                  name + "." + param + " is " + range + ")");
    bool set = false;
    try {  // OMPL's conversion of a real number throws past its own setValue
      set = planner->params().setParam(param, value);
    } catch (const std::exception& e) {
      throw std::invalid_argument("flag --set " + key + "=" + value + ": " + e.what());
    }
    if (!set)
      throw std::invalid_argument("flag --set " + key + "=" + value + ": planner '" + name + "' refused the value");
  }
  return planner;
}

// Every segment of `path` proven collision-free, end points included, by the world's certifier
// (cspace/certified_motion_validator.hpp).
bool provenPath(og::PathGeometric& path, const ompl_planners::ScenarioWorld& world) {
  const planners::PlanningContext& context = world.context();
  const std::vector<ob::State*>& states = path.getStates();
  if (states.empty() || !context.certifier) return false;
  Eigen::VectorXd a = ompl_planners::toConfiguration(states.front(), context.space);
  if (states.size() == 1) return context.certifier->isValid(a, a);
  for (size_t i = 1; i < states.size(); ++i) {
    const Eigen::VectorXd b = ompl_planners::toConfiguration(states[i], context.space);
    if (!context.certifier->isValid(a, b)) return false;
    a = b;
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  Flags flags;
  try {
    flags = parseFlags(argc, argv);
  } catch (const std::invalid_argument& e) {
    const bool help = std::string(e.what()).empty();
    (help ? std::cout : std::cerr) << (help ? "" : std::string("svmp-ompl-benchmark: ") + e.what() + "\n") << kUsage;
    return help ? 0 : 2;
  }
  ompl::RNG::setSeed(flags.seed);  // before any OMPL generator exists, or it is ignored
  try {
    experiments::checkDistinct({{"--scenario", flags.scenario}, {"--log", flags.log}}, {});
    experiments::checkWritable("--log", flags.log);
    cspace::Scenario scenario = cspace::loadScenario(flags.scenario);
    experiments::requireValidConfigurations(scenario);
    if (flags.query >= static_cast<int>(scenario.queries.size()))
      throw std::invalid_argument("flag --query: " + std::to_string(flags.query) + ": the scenario has " +
                                  std::to_string(scenario.queries.size()) + " queries");
    const std::string name = scenario.name;
    const auto world = ompl_planners::ScenarioWorld::make(std::move(scenario), flags.threads);
    const auto setup = world->simpleSetup(flags.query);
    ompl::tools::Benchmark benchmark(*setup, name);
    for (const std::string& planner : flags.planners)
      benchmark.addPlanner(makePlanner(planner, setup->getSpaceInformation(), world->scenario(), flags.sets));
    benchmark.addExperimentParameter("scenario_file", "TEXT", world->scenario().path);
    benchmark.addExperimentParameter("threads", "INTEGER", std::to_string(flags.threads));
    // Our checker's count over each run, OMPL's planners and ours counted alike. Benchmark checks a
    // found path twice (correct solution, strict) before the post-run event; our validator ignores
    // OMPL's segment count factor, so both cost one more check() and are taken off.
    std::uint64_t checks_before = 0;
    benchmark.setPreRunEvent([&](const ob::PlannerPtr&) { checks_before = world->checker().collisionChecks(); });
    benchmark.setPostRunEvent([&](const ob::PlannerPtr& planner, ompl::tools::Benchmark::RunProperties& run) {
      std::uint64_t checks = world->checker().collisionChecks() - checks_before;
      if (setup->haveSolutionPath()) {
        const std::uint64_t before = world->checker().collisionChecks();
        setup->getSolutionPath().check();
        checks -= 2 * (world->checker().collisionChecks() - before);
      }
      run["collision checks INTEGER"] = std::to_string(checks);
      const auto* ours = dynamic_cast<const ompl_planners::SvmOmplPlannerBase*>(planner.get());
      if (ours) run.merge(experiments::counterProperties(ours->lastResult()));
      // OMPL's planners check motions by samples at the resolution and can step over a wall thinner
      // than that; their exact solutions are proven here, after the run and outside its time, as
      // svmp-plan proves every path (ours prove theirs in the run). A path not proven, or one that
      // stops short of the goal, is not a correct solution.
      const bool certified = ours ? ours->lastResult().certified
                                  : setup->haveExactSolutionPath() && provenPath(setup->getSolutionPath(), *world);
      run["certified BOOLEAN"] = std::to_string(static_cast<int>(certified));
      if (!certified)
        for (const char* key : {"correct solution BOOLEAN", "correct solution strict BOOLEAN"})
          if (run.count(key)) run[key] = "0";
    });
    std::cerr << "svmp-ompl-benchmark: " << name << ": " << flags.planners.size() << " planners, " << flags.runs
              << " runs each, at most " << flags.time_limit << " s per run\n";
    benchmark.benchmark(ompl::tools::Benchmark::Request(flags.time_limit, 4096.0, flags.runs, 0.05, false, false, false));
    std::ostringstream log;
    if (!benchmark.saveResultsToStream(log)) throw std::runtime_error("OMPL's Benchmark recorded no results");
    experiments::writeFileAtomically(flags.log, log.str());
    for (const auto& planner : benchmark.getRecordedExperimentData().planners) {
      int solved = 0, certified = 0;
      std::map<std::string, int> statuses;  // ours' own status names, else OMPL's
      for (const auto& run : planner.runs) {
        solved += run.count("solved BOOLEAN") && run.at("solved BOOLEAN") == "1";
        certified += run.count("certified BOOLEAN") && run.at("certified BOOLEAN") == "1";
        if (run.count("svmp status TEXT")) ++statuses[run.at("svmp status TEXT")];
        else if (run.count("status ENUM"))
          ++statuses[ob::PlannerStatus(static_cast<ob::PlannerStatus::StatusType>(std::stoi(run.at("status ENUM"))))
                         .asString()];
      }
      std::cout << planner.name << ": " << solved << "/" << planner.runs.size() << " solved, " << certified
                << " certified collision-free (";
      for (auto it = statuses.begin(); it != statuses.end(); ++it)
        std::cout << (it == statuses.begin() ? "" : ", ") << it->first << " " << it->second;
      std::cout << ")\n";
    }
    std::cerr << "svmp-ompl-benchmark: wrote " << flags.log << "\n";
    return 0;
  } catch (const cspace::ScenarioError& e) {
    std::cerr << "svmp-ompl-benchmark: " << e.what() << "\n";
  } catch (const std::invalid_argument& e) {
    std::cerr << "svmp-ompl-benchmark: " << flags.scenario << ": " << e.what() << "\n";
  } catch (const std::runtime_error& e) {
    std::cerr << "svmp-ompl-benchmark: " << e.what() << "\n";
  }
  return 2;
}
