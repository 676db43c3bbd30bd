#include "bench/experiments/experiment.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <memory>
#include <set>
#include <sstream>

#include <unistd.h>

#include "bench/experiments/output_text.hpp"
#include "bench/experiments/scenario_check.hpp"
#include "bench/experiments/svg_writer.hpp"
#include "bench/experiments/svpp_svg.hpp"
#include "cspace/certified_motion_validator.hpp"
#include "cspace/collision_checker.hpp"
#include "cspace/fastron_checker.hpp"
#include "cspace/motion_validator.hpp"
#include "planners/exact_setup.hpp"
#include "planners/path_simplifier.hpp"
#include "planners/planner_registry.hpp"
#include "planners/svpp_smoothing.hpp"
#include "planners/verify_repair.hpp"
#include "robots/point_robot.hpp"
#include "svm/solver_workspace.hpp"

namespace svmp::experiments {
namespace {

using Clock = planners::Clock;

// The process' resident memory (Linux /proc/self/statm); 0 where it cannot be read.
double residentMegabytes() {
  std::ifstream statm("/proc/self/statm");
  long pages = 0, resident = 0;
  if (!(statm >> pages >> resident)) return 0;
  return static_cast<double>(resident) * static_cast<double>(sysconf(_SC_PAGESIZE)) / (1024.0 * 1024.0);
}

// Path quality measured by an independent checker, so the planners' counters are untouched.
void measurePath(const cspace::Scenario& scenario, const cspace::ConfigurationSpace& space,
                 const cspace::CollisionChecker& checker, RunRecord& record) {
  const auto& path = record.result.path;
  if (path.empty()) return;
  record.path_length = planners::pathLength(path, space);
  record.smoothness = planners::smoothness(path, space);
  record.min_clearance = planners::minClearance(path, checker, space, scenario.resolution / 4);
}

// The scenario's parameters of `name` (a planner, a proxy checker, svpp's smoothing) with --set's.
cspace::ParameterSet parametersFor(const std::string& name, const cspace::Scenario& scenario,
                                   const DriverOptions& options) {
  cspace::ParameterSet params = scenario.paramsFor(name);
  for (const auto& [key, value] : options.overrides)
    if (key.rfind(name + ".", 0) == 0) params.set(key.substr(name.size() + 1), value, "flag --set " + key + "=" + value);
  return params;
}

// Every `planners:` section names a planner or a proxy checker: a typo (`prmm:`) would otherwise leave
// the planner on its defaults without a word.
void checkPlannerSections(const cspace::Scenario& scenario) {
  const std::vector<std::string> planners = planners::plannerNames();
  const bool has_ompl = std::find(planners.begin(), planners.end(), "ompl-prm") != planners.end();
  for (const auto& [name, params] : scenario.planner_params) {
    if (std::find(planners.begin(), planners.end(), name) != planners.end() ||
        (isCheckerName(name) && name != "fcl") || (!has_ompl && name.rfind("ompl-", 0) == 0))
      continue;
    std::string known;
    for (const auto& n : planners) known += n + ", ";
    throw cspace::ScenarioError(scenario.path + ": field 'planners." + name + "': unknown planner (known: " + known +
                                "fastron-fk, fastron-rbf)");
  }
}

// --simplify svpp: the smoothing's options, from the scenario's svpp section and --set svpp.*.
planners::SvppOptions svmSmoothingOptions(const cspace::Scenario& scenario, const DriverOptions& options) {
  const cspace::ParameterSet params = parametersFor("svpp", scenario, options);
  const auto svpp = planners::SvppOptions::fromParameters(params);
  params.requireAllUsed();
  const cspace::ConfigurationSpace space = scenario.makeSpace();
  planners::SvppOptions::requireKeysFor(params, space.dim());
  if (const std::string why = svpp.resolvedFor(space, scenario.environment->numReal()).validateFor(space); !why.empty())
    throw cspace::ScenarioError(scenario.path + ": --simplify svpp: svpp parameters: " + why);
  if (!dynamic_cast<const robots::PointRobot*>(scenario.robot.get()))
    throw cspace::ScenarioError(scenario.path + ": --simplify svpp smooths the paths of point robots in 2-D and 3-D; "
                                "the robot is '" + scenario.robot->name() + "' (use --simplify)");
  return svpp;
}

// One parameter of a planner or proxy as a run uses it: its value (derived from the problem where
// the planner derived it, else as set or its default), where that comes from, and its range.
struct ParameterUse {
  std::string key, value, source, range;
};

std::vector<ParameterUse> parameterUses(const cspace::ParameterSet& params,
                                        const std::map<std::string, std::string>& derived = {}) {
  std::vector<ParameterUse> uses;
  for (const auto& [key, declaration] : params.declarations()) {
    const auto d = derived.find(key);
    const std::string given = params.has(key) ? params.values().at(key) : declaration.fallback;
    const std::string value = d != derived.end() ? d->second : given;
    const char* source = params.has(key) ? "set" : value != given ? "derived" : "default";
    uses.push_back({key, value, source, declaration.range});
  }
  return uses;
}

// With --checker fastron-*: the proxy (trained once, on the scenario's query end points too) and the
// thesis' sampled validator on it; World's repairer verifies and repairs on the exact checker (Das &
// Yip 2019, sec. IV-B).
struct Proxy {
  Proxy(const cspace::Scenario& scenario, const DriverOptions& options, const planners::PlanningContext& exact,
        std::ostream& log) {
    const cspace::ParameterSet params = parametersFor(options.checker, scenario, options);
    auto o = cspace::FastronCheckerOptions::fromParameters(options.checker, params);
    params.requireAllUsed();
    parameters = parameterUses(params);
    o.threads = options.threads;
    checker = std::make_unique<cspace::FastronChecker>(scenario.robot, o);
    std::vector<Eigen::VectorXd> ends;
    for (const auto& q : scenario.queries) ends.push_back(q.start), ends.push_back(q.goal);
    // Learning comes before the runs; a --time-limit bounds it as it bounds each run.
    const planners::Termination stop =
        options.time_limit > 0 ? planners::Termination::after(options.time_limit) : planners::Termination();
    const auto s = checker->train(exact.checker, options.seed, ends, stop.asFunction());
    if (s.train.stopped)
      throw std::runtime_error((std::ostringstream() << "flag --time-limit " << options.time_limit << ": the "
                                                     << options.checker << " proxy had not learned its " << s.labelled
                                                     << " configurations after " << s.train.steps << " updates")
                                   .str());
    log << "svmp-plan: " << options.checker << ": " << s.labelled << " configurations labelled in " << s.label_ms
        << " ms, learned in " << s.learn_ms << " ms: " << s.train.support << " support points"
        << (s.train.converged ? "" : " (not converged)") << "\n";
    if (!s.train.converged)
      warnings.push_back(options.checker + " stopped learning after " + std::to_string(s.train.steps) +
                         " updates, not converged: some of its labelled configurations are predicted wrong");
    validator = std::make_unique<cspace::DiscreteMotionValidator>(*checker, exact.space, scenario.resolution);
    warnOfClosedPassages(scenario, exact, options.checker, log);
  }
  // A proxy that predicts a query's start or goal, or the file's free witness path, in collision has
  // closed a passage the queries need (a narrow gap the labelled samples missed): planning on it may
  // fail, which the user should know before blaming the planners.
  void warnOfClosedPassages(const cspace::Scenario& scenario, const planners::PlanningContext& exact,
                            const std::string& name, std::ostream& log) {
    const cspace::ConfigurationSpace& space = exact.space;
    query_warnings.assign(scenario.queries.size(), {});
    for (size_t i = 0; i < scenario.queries.size(); ++i) {
      const cspace::Query& query = scenario.queries[i];
      const auto warn = [&](const std::string& text) {
        log << "svmp-plan: warning: " << text << "\n";
        query_warnings[i].push_back(text);
      };
      // A free configuration (a witness that collides is --check's) the proxy predicts in collision.
      const auto closes = [&](const Eigen::VectorXd& c) { return exact.checker.isValid(c) && !checker->isValid(c); };
      // The ends, with or without a witness: a proxy that puts one in collision leaves no path.
      for (const auto& [end, which] : {std::pair{&query.start, "start"}, std::pair{&query.goal, "goal"}})
        if (closes(*end))
          warn(name + " predicts query " + std::to_string(i) + "'s " + which +
               " in collision (free on the exact checker): planning on it may fail");
      const std::vector<Eigen::VectorXd> path = query.witnessPath();
      long predicted = 0, tested = 0;  // along the witness path, its ends left out
      Eigen::VectorXd c(space.dim());
      for (size_t k = 0; k + 1 < path.size(); ++k) {
        const double length = space.distance(path[k], path[k + 1]);
        const long parts = std::max(1L, static_cast<long>(std::ceil(length / scenario.resolution)));
        for (long j = k == 0 ? 1 : 0; j < parts && tested < 1000000; ++j, ++tested) {
          space.interpolate(path[k], path[k + 1], static_cast<double>(j) / parts, c);
          predicted += closes(c);
        }
      }
      if (predicted > 0)
        warn(name + " predicts " + std::to_string(predicted) + " of " + std::to_string(tested) +
             " configurations along query " + std::to_string(i) + "'s witness path (free on the exact checker) in "
             "collision: the proxy closes a passage that path takes, and planning on it may fail (docs/fastron.md)");
    }
  }
  std::unique_ptr<cspace::FastronChecker> checker;
  std::unique_ptr<cspace::DiscreteMotionValidator> validator;  // the thesis' sampled validator, on the proxy
  // What the runs on it are told (their JSON records, Plan.warnings): every run, and query i's runs.
  std::vector<std::string> warnings;
  std::vector<std::vector<std::string>> query_warnings;
  std::vector<ParameterUse> parameters;
};

// Everything a run shares: the exact setup (space, FCL checker, the thesis' sampled validator, the
// certifier, the repairer) and an independent checker for measurements. Planners see `context`: the
// exact checker or the proxy, and a repairer that verifies every non-roadmap path and replans its
// failing stretches on `exact` (with the exact checker, segments that clip an obstacle between sampled
// checks).
struct World : planners::ExactSetup {
  World(const cspace::Scenario& scenario, const DriverOptions& options, std::ostream& log)
      : ExactSetup(scenario, options.threads),
        measuring(scenario.robot, scenario.environment, scenario.self_collision),
        proxy(options.checker == "fcl" ? nullptr : std::make_unique<Proxy>(scenario, options, exact, log)),
        context{space, proxy ? static_cast<const cspace::ValidityChecker&>(*proxy->checker) : checker,
                proxy ? static_cast<const cspace::MotionValidator&>(*proxy->validator) : validator, options.threads,
                &certifier, &repairer} {}
  const cspace::CollisionChecker measuring;
  const std::unique_ptr<Proxy> proxy;
  const planners::PlanningContext context;
};

// The file's sections of planners and proxies this run does not use are read too: a typo or a bad
// value there is an error as anywhere in the file, not found only by the run that uses it.
void readSectionsNotRun(const cspace::Scenario& scenario, const DriverOptions& options,
                        const planners::PlanningContext& context) {
  const std::vector<std::string> registered = planners::plannerNames();
  for (const auto& [name, section] : scenario.planner_params) {
    if (std::find(options.planners.begin(), options.planners.end(), name) != options.planners.end() ||
        name == options.checker)
      continue;
    if (std::find(registered.begin(), registered.end(), name) != registered.end()) {
      const cspace::ParameterSet params = scenario.paramsFor(name);
      try {
        planners::makePlanner(name, context, params);
      } catch (const cspace::ScenarioError& e) {
        // An error about a value the section sets is the file's to mend; one its defaults meet on
        // this problem (svpp's virtual samples for an arm of 8 joints) waits for a run of it.
        for (const auto& [key, value] : params.values())
          if (std::string(e.what()).find(params.describe(key)) != std::string::npos) throw;
        params.requireAllUsed();  // the factory read every key it knows before it judged the problem
      }
    } else if (cspace::isFastronCheckerName(name)) {
      const cspace::ParameterSet params = scenario.paramsFor(name);
      cspace::FastronCheckerOptions::fromParameters(name, params);
      params.requireAllUsed();
    }
  }
}

// The planners of --planners with the scenario's parameters and --set; `parameters` (when given) gets
// each one's parameters as used.
std::vector<std::unique_ptr<planners::Planner>> makePlanners(
    const cspace::Scenario& scenario, const DriverOptions& options, const planners::PlanningContext& context,
    std::vector<std::vector<ParameterUse>>* parameters = nullptr) {
  checkPlannerSections(scenario);
  std::vector<std::unique_ptr<planners::Planner>> planners;
  for (const auto& name : options.planners) {
    const cspace::ParameterSet params = parametersFor(name, scenario, options);
    planners.push_back(planners::makePlanner(name, context, params));
    if (!parameters) continue;
    parameters->push_back(parameterUses(params, planners.back()->derivedParameters()));
  }
  readSectionsNotRun(scenario, options, context);
  return planners;
}

// Every name of --planners is a registered planner, and every --set names one of them, the proxy
// checker of --checker or --simplify svpp's smoothing; checked before the proxy learns (minutes on an
// arm).
void checkPlannersAndOverrides(const DriverOptions& options) {
  const std::vector<std::string> registered = planners::plannerNames();
  for (const auto& name : options.planners)
    if (std::find(registered.begin(), registered.end(), name) == registered.end())
      throw cspace::ScenarioError("flag --planners: " + planners::unknownPlanner(name));
  for (const auto& [key, value] : options.overrides) {
    const std::string target = key.substr(0, key.find('.'));
    if (target == options.checker) continue;  // the proxy checker's own parameters
    if (target == "svpp" && options.simplify_svm) continue;  // the smoothing's
    if (isCheckerName(target))
      throw cspace::ScenarioError("flag --set " + key + "=" + value + ": '" + target + "' is a checker, and --checker is " +
                                  options.checker);
    if (std::find(options.planners.begin(), options.planners.end(), target) == options.planners.end())
      throw cspace::ScenarioError("flag --set " + key + "=" + value + ": planner '" + target +
                                  "' is not among --planners");
  }
}

// Pictures of one run (thesis Figs 3.1-3.8, 4.5, 4.7): what the planner learned and its path.
void writePictures(const std::string& dir, const cspace::Scenario& scenario, const planners::Planner& planner,
                   const RunRecord& record, std::ostream& log) {
  SvgContent content;
  content.scenario = &scenario;
  content.path = &record.result.path;
  content.title = scenario.name + ": " + planner.name() + " (" + planners::planStatusName(record.result.status) + ")";
  const planners::PlannerView view = planner.view();
  content.samples = view.samples;
  content.risk = view.risk;
  content.roadmap = view.roadmap;
  const std::string base = dir + "/" + safeFileName(scenario.name + "_" + planner.name());
  std::vector<std::string> wrote;
  if (writeConfigurationSpaceSvg(base + "_cspace.svg", content)) wrote.push_back(base + "_cspace.svg");
  if (writeWorkspaceSvg(base + "_workspace.svg", content)) wrote.push_back(base + "_workspace.svg");
  if (view.svpp && writeSvppSvg(base + "_svpp.svg", content.title, *view.svpp, scenario.robot->lowerLimits(),
                                scenario.robot->upperLimits()))
    wrote.push_back(base + "_svpp.svg");
  for (const std::string& file : wrote) log << "  wrote " << file << "\n";
  if (wrote.empty())
    log << "  --svg: no picture of " << planner.name() << " on '" << scenario.robot->name()
        << "' (pictures draw 2-D configuration spaces and planar workspaces)\n";
}

}  // namespace

int PlannerRuns::solved() const {
  return static_cast<int>(std::count_if(runs.begin(), runs.end(), [](const RunRecord& r) { return r.result.solved(); }));
}

int PlannerRuns::certified() const {
  return static_cast<int>(std::count_if(runs.begin(), runs.end(), [](const RunRecord& r) { return r.result.certified; }));
}

std::vector<cspace::Query> randomQueries(const cspace::Scenario& scenario, int count, std::uint64_t seed) {
  const cspace::ConfigurationSpace space = scenario.makeSpace();
  const cspace::CollisionChecker checker(scenario.robot, scenario.environment, scenario.self_collision);
  cspace::Rng rng(seed ^ 0x51E7D0C5ULL);
  std::vector<cspace::Query> queries;
  auto draw = [&](Eigen::VectorXd& q) {
    for (long tries = 0; tries < 1000; ++tries)
      if (space.sampleUniform(rng, q), checker.isValid(q)) return true;
    return false;
  };
  Eigen::VectorXd start(space.dim()), goal(space.dim());
  while (static_cast<int>(queries.size()) < count) {
    if (!draw(start) || !draw(goal))
      throw cspace::ScenarioError(scenario.path + ": --queries " + std::to_string(count) + ": 1000 uniform draws in a row "
                                  "found no valid configuration (after " + std::to_string(queries.size()) + " pairs)");
    if (start != goal) queries.push_back({start, goal, {}});
  }
  return queries;
}

bool sharedBuild(const cspace::Scenario& scenario, const DriverOptions& options) {
  return scenario.queries.size() > 1 || options.queries > 0;
}

void validatePlanners(const cspace::Scenario& scenario, const DriverOptions& options, std::ostream* out) {
  checkPlannersAndOverrides(options);
  std::ostringstream quiet;
  const World world(scenario, options, quiet);
  std::vector<std::vector<ParameterUse>> parameters;
  makePlanners(scenario, options, world.context, &parameters);
  if (options.simplify_svm) svmSmoothingOptions(scenario, options);
  if (!out) return;
  std::vector<std::string> owners = options.planners;
  if (world.proxy) parameters.push_back(world.proxy->parameters), owners.push_back(options.checker);
  for (size_t p = 0; p < parameters.size(); ++p)
    for (const ParameterUse& u : parameters[p])
      *out << "parameter  " << owners[p] << "." << u.key << " = " << u.value << "  (" << u.source
           << (u.range.empty() ? "" : ", " + u.range) << ")\n";
}

std::vector<PlannerRuns> runExperiment(const cspace::Scenario& scenario, const DriverOptions& options,
                                       std::ostream& log) {
  checkPlannersAndOverrides(options);
  // Before the proxy learns: a bad smoothing parameter or robot must not wait for it.
  const auto smoothing_options = options.simplify_svm ? svmSmoothingOptions(scenario, options) : planners::SvppOptions();
  const World world(scenario, options, log);
  for (const auto& [a, b] : world.checker.droppedSelfCollisionPairs())
    log << "svmp-plan: " << droppedPairWarning(a, b) << " (--check)\n";
  // Every planner is built first: a bad parameter stops the run before any work.
  std::vector<std::vector<ParameterUse>> parameters;
  auto planners = makePlanners(scenario, options, world.context, &parameters);
  std::vector<PlannerRuns> results;
  for (size_t p = 0; p < planners.size(); ++p) {
    results.push_back({options.planners[p], {}, {}});
    for (const ParameterUse& u : parameters[p]) results.back().parameters[u.key] = u.value;
  }
  const auto& queries = scenario.queries;
  const bool shared_build = sharedBuild(scenario, options);
  svm::SolverWorkspace smoothing;  // --simplify svpp: each path's SVM reuses the last one's cache memory
  std::vector<std::set<std::string>> warned(planners.size());  // per planner, the warnings logged
  std::vector<int> later_warnings(planners.size(), 0);        // ... and how many after its first run
  // Seed by seed, every planner in turn: a change of load while the run lasts slows each planner
  // alike, so their ratios stay fair (one planner's runs all after another's would not).
  for (int r = 0; r < options.runs; ++r) {
    const std::uint64_t seed = options.seed + r;
    for (size_t p = 0; p < planners.size(); ++p) {
      PlannerRuns& runs = results[p];
      planners::Planner& planner = *planners[p];
      // The limit holds for each solve: the build, and each query on its own. A limit for the whole run
      // would let one query that no planner solves use it up, and every later query fail untried.
      const auto limit = [&] {
        return options.time_limit > 0 ? planners::Termination::after(options.time_limit) : planners::Termination();
      };
      // One query: solve() (clear, build, answer). Several, or --queries: one build per run answers
      // them all; the first query's record carries the build, later ones what one more query costs.
      // A build that fails fails every query, the first record carrying its time and counters.
      planners::PlanResult build;
      double build_ms = 0;
      if (shared_build) {
        const auto t0 = Clock::now();
        build = planner.build(seed, limit());
        build_ms = planners::msSince(t0);
      }
      for (size_t i = 0; i < queries.size(); ++i) {
        RunRecord record;
        record.seed = seed;
        record.query = static_cast<int>(i);
        const double resident_mb = residentMegabytes();
        const planners::Termination stop = limit();
        const auto t0 = Clock::now();
        if (!shared_build) {
          record.result = planner.solve(queries[i], seed, stop);
        } else if (!planner.built()) {
          if (i == 0) record.result = build;
          record.result.status = build.status;
          record.result.message = build.message;
        } else {
          record.result = planner.query(queries[i], seed, stop);
        }
        record.time_ms = planners::msSince(t0) - record.result.counting_ms;
        record.memory_mb = std::max(0.0, residentMegabytes() - resident_mb);
        if (i == 0 && shared_build) {
          record.time_ms += build_ms;
          record.build_ms = build_ms;
          if (planner.built()) planners::addBuild(build, record.result);
        }
        record.raw_length = planners::pathLength(record.result.path, world.space);
        const size_t planner_warnings = record.result.warnings.size();  // the proxy's and smoothing's come after
        if (world.proxy)
          for (const auto* told : {&world.proxy->warnings, &world.proxy->query_warnings[i]})
            record.result.warnings.insert(record.result.warnings.end(), told->begin(), told->end());
        if (options.simplify && record.result.solved()) {
          const auto t1 = Clock::now();
          if (options.simplify_svm) {
            // --time-limit bounds the smoothing of each path as it bounds each solve.
            auto smoothed = planners::smoothPathBySvm(record.result.path, world.checker, world.certifier,
                                                      world.space, smoothing_options, &smoothing, limit().asFunction());
            if (!smoothed.smoothed) {  // in the JSON record too, which then says which paths are smoothed
              log << "  " << runs.planner << " seed " << seed << ": path kept (" << smoothed.why << ")\n";
              record.result.warnings.push_back("--simplify svpp kept the path as planned: " + smoothed.why);
            }
            record.result.path = std::move(smoothed.path);
          } else {
            cspace::Rng rng(seed ^ 0x5157A9E1ULL);
            record.result.path = planners::simplifyPath(record.result.path, world.certifier, world.space, rng).path;
          }
          record.simplify_ms = planners::msSince(t1);
        }
        measurePath(scenario, world.space, world.measuring, record);
        if (r == 0 && i == 0 && !options.svg_dir.empty()) writePictures(options.svg_dir, scenario, planner, record, log);
        if (planner.built() || i == 0)  // a failed build is logged once, not for every query
          log << "  " << runs.planner << " seed " << seed << (shared_build ? " query " + std::to_string(i) : "")
              << ": " << planners::planStatusName(record.result.status) << ", " << record.result.collision_checks
              << " checks, " << std::fixed << std::setprecision(1) << record.time_ms << " ms"
              << (record.result.message.empty() ? "" : " (" + record.result.message + ")") << "\n";
        // Each warning once (the smoothing's: logged above); later seeds' only where new, up to
        // kLaterWarnings a planner (texts with counts differ from seed to seed): a root search that
        // misses an obstacle on one seed may find it on another. Every record keeps its own.
        constexpr int kLaterWarnings = 5;
        for (size_t w = 0; w < planner_warnings; ++w) {
          if (!warned[p].insert(record.result.warnings[w]).second) continue;
          const bool later = r > 0 || i > 0;
          if (later && ++later_warnings[p] > kLaterWarnings) {
            if (later_warnings[p] == kLaterWarnings + 1)
              log << "  " << runs.planner << ": more warnings of later runs are in the records (--json)\n";
            continue;
          }
          log << "  " << runs.planner << " warning" << (later ? " (seed " + std::to_string(seed) + ")" : "") << ": "
              << record.result.warnings[w] << "\n";
        }
        runs.runs.push_back(std::move(record));
      }
    }
  }
  return results;
}

}  // namespace svmp::experiments
