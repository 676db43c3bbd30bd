// svmp.load_scenario, svmp.Scenario (its exact FCL collision checker, metric and queries) and svmp.plan:
// one run of a registered planner exactly as svmp-plan does it (bench/experiments/experiment.hpp: the
// certifier, verify and repair, path measurements), so a seed gives the same result here as there.
#include <pybind11/stl.h>

#include <pthread.h>

#include <atomic>
#include <memory>
#include <sstream>
#include <typeinfo>

#include "bench/experiments/experiment.hpp"
#include "bench/experiments/scenario_check.hpp"
#include "cspace/collision_checker.hpp"
#include "planners/planner_registry.hpp"
#include "python/arrays.hpp"
#include "python/bindings.hpp"

namespace svmp::python {
namespace {

struct Scenario {
  explicit Scenario(cspace::Scenario s)
      : scenario(std::move(s)),
        space(scenario.makeSpace()),
        checker(std::make_unique<cspace::CollisionChecker>(scenario.robot, scenario.environment, scenario.self_collision)) {}
  Eigen::VectorXd point(const py::object& q, const char* name) const {
    return vectorFromArray(q, name, scenario.robot->dof());
  }
  cspace::Scenario scenario;
  cspace::ConfigurationSpace space;
  std::unique_ptr<cspace::CollisionChecker> checker;  // exact, FCL
};

struct Plan {
  std::string planner, status, message;
  std::vector<std::string> warnings;
  std::uint64_t seed = 0;
  bool solved = false, certified = false;
  py::array_t<double> path;
  py::dict counters;
};

// A --set value as svmp-plan would read it from the command line. NumPy scalars (np.float64(0.4),
// np.bool_) are read as the Python values they hold, not as their repr.
std::string parameterText(const py::handle& given) {
  const py::object value = py::hasattr(given, "item") && py::hasattr(given, "dtype") ? given.attr("item")()
                                                                                   : py::reinterpret_borrow<py::object>(given);
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>() ? "true" : "false";
  if (py::isinstance<py::float_>(value)) return py::str(py::repr(py::float_(value)));  // shortest round-trip digits
  return py::str(value);
}

// libgomp's thread pool does not survive fork(): a process forked from one that ran a parallel region
// waits forever in its first own (multiprocessing's default start method on Linux). Such a child plans
// on one thread, which gives the same result, and says so.
std::atomic<bool> parallel_used{false};
bool forked_after_parallel = false;
void afterForkInChild() { forked_after_parallel = parallel_used.load(); }

Plan plan(const Scenario& s, const std::string& planner, const py::object& seed_in, const py::dict& params,
          const py::object& query_in, const std::string& checker, double time_limit, const py::object& threads_in,
          const py::object& simplify) {
  const long long seed = integerArgument(integerValue(seed_in, "seed"), "seed", 0, experiments::kMaxSeed, "must be in [0, 2^62]");
  const int queries = static_cast<int>(s.scenario.queries.size());
  const int query = static_cast<int>(integerArgument(integerValue(query_in, "query"), "query", 0, queries - 1,
                                                     "the scenario has " + std::to_string(queries) + " quer" +
                                                         (queries == 1 ? "y" : "ies")));
  int threads = static_cast<int>(integerArgument(integerValue(threads_in, "threads"), "threads", 1, experiments::kMaxThreads,
                                                 "must be in [1, " + std::to_string(experiments::kMaxThreads) + "]"));
  if (threads > 1 && forked_after_parallel) {
    if (PyErr_WarnEx(PyExc_RuntimeWarning,
                     "svmp.plan: this process was forked after svmp planned on several threads, and OpenMP "
                     "cannot run threads in it (it would hang): planning on 1 thread, with the same result. "
                     "Use multiprocessing.get_context('spawn') for more.",
                     1) != 0)
      throw py::error_already_set();
    threads = 1;
  }
  if (threads > 1) parallel_used = true;
  if (!experiments::isCheckerName(checker))
    throw py::value_error("checker is '" + checker + "': expected fcl, fastron-fk or fastron-rbf");
  if (!(time_limit >= 0)) throw py::value_error("time_limit is " + numberText(time_limit) + ": must be >= 0 (0: none)");
  experiments::DriverOptions options;
  options.scenario = s.scenario.path;
  options.planners = {planner};
  options.seed = static_cast<unsigned long>(seed);
  options.threads = threads;
  options.time_limit = time_limit;
  options.checker = checker;
  if (py::isinstance<py::bool_>(simplify)) {
    options.simplify = simplify.cast<bool>();
  } else if (py::isinstance<py::str>(simplify) && simplify.cast<std::string>() == "svpp") {
    options.simplify = options.simplify_svm = true;  // svmp-plan --simplify svpp
  } else {
    throw py::value_error("simplify is " + std::string(py::repr(simplify)) + ": expected False, True or 'svpp'");
  }
  // The driver's messages name "flag --set PLANNER.KEY=VALUE"; here they name params['KEY'].
  std::vector<std::pair<std::string, std::string>> flag_names;
  for (const auto& [key, value] : params) {
    const std::string name = py::str(key);
    // "sigma" is the planner's own; "fastron-fk.gamma" names a checker's parameter in full.
    const std::string full = name.find('.') == std::string::npos ? planner + "." + name : name;
    const std::string text = parameterText(value);
    flag_names.emplace_back("flag --set " + full + "=" + text, "params['" + name + "'] = " + text);
    try {
      experiments::addOverride(options, full, text);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string("params: ") + e.what());
    }
  }
  flag_names.emplace_back("is not among --planners", "is not the planner run ('" + planner + "')");
  flag_names.emplace_back("--checker is ", "checker is ");
  flag_names.emplace_back("flag --time-limit ", "time_limit = ");
  const auto inPythonTerms = [&](std::string message) {
    for (const auto& [flag, param] : flag_names)
      for (size_t at; (at = message.find(flag)) != std::string::npos;) message.replace(at, flag.size(), param);
    return message;
  };
  cspace::Scenario one = s.scenario;
  one.queries = {s.scenario.queries[query]};
  experiments::requireValidConfigurations(one);  // as svmp-plan: a start in collision, a sample off its obstacle
  experiments::RunRecord record;
  try {
    py::gil_scoped_release release;
    std::ostringstream log;
    record = experiments::runExperiment(one, options, log).front().runs.front();
  } catch (const cspace::ScenarioError& e) {
    throw cspace::ScenarioError(inPythonTerms(e.what()));
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(inPythonTerms(e.what()));
  } catch (const std::runtime_error& e) {
    if (typeid(e) != typeid(std::runtime_error)) throw;  // a subtype keeps its Python exception
    throw std::runtime_error(inPythonTerms(e.what()));
  }
  const planners::PlanResult& r = record.result;
  Plan out;
  out.planner = planner;
  out.status = planners::planStatusName(r.status);
  out.message = r.message;
  out.warnings = r.warnings;
  // The run planned a copy of the scenario holding this one query, which its warnings call query 0.
  const std::string as_run = "query 0's", as_asked = "query " + std::to_string(query) + "'s";
  for (std::string& w : out.warnings)
    for (size_t at = 0; (at = w.find(as_run, at)) != std::string::npos; at += as_asked.size()) w.replace(at, as_run.size(), as_asked);
  out.seed = static_cast<std::uint64_t>(seed);
  out.solved = r.solved();
  out.certified = r.certified;
  out.path = pointsToArray(r.solved() ? r.path : std::vector<Eigen::VectorXd>{}, s.scenario.robot->dof());
  const std::pair<const char*, std::uint64_t> counts[] = {
      {"collision_checks", r.collision_checks}, {"local_planner_calls", r.local_planner_calls},
      {"distance_queries", r.distance_queries}, {"certified_segments", r.certified_segments},
      {"milestones", r.milestones},             {"roadmap_edges", r.roadmap_edges},
      {"support_vectors", r.support_vectors},   {"repaired_stretches", std::uint64_t(r.repaired_stretches)},
      {"exact_checks", r.exact_checks}};
  const std::pair<const char*, double> measures[] = {
      {"time_ms", record.time_ms},          {"path_length", record.path_length},
      {"raw_length", record.raw_length},    {"smoothness", record.smoothness},
      {"min_clearance", record.min_clearance}, {"sampling_ms", r.times.sampling_ms},
      {"training_ms", r.times.training_ms}, {"milestones_ms", r.times.milestones_ms},
      {"roadmap_ms", r.times.roadmap_ms},   {"query_ms", r.times.query_ms},
      {"certify_ms", r.times.certify_ms}};
  for (const auto& [name, value] : counts) out.counters[name] = value;
  for (const auto& [name, value] : measures) out.counters[name] = value;
  return out;
}

}  // namespace

void bindPlanning(py::module_& m) {
  py::class_<Scenario>(m, "Scenario", "A scenario file: robot, obstacles, queries, resolution, planner parameters.")
      .def_property_readonly("name", [](const Scenario& s) { return s.scenario.name; })
      .def_property_readonly("path", [](const Scenario& s) { return s.scenario.path; })
      .def_property_readonly("dof", [](const Scenario& s) { return s.scenario.robot->dof(); })
      .def_property_readonly("resolution", [](const Scenario& s) { return s.scenario.resolution; },
                             "collision-checking resolution in the weighted metric")
      .def_property_readonly("lower", [](const Scenario& s) { return vectorToArray(s.scenario.robot->lowerLimits()); })
      .def_property_readonly("upper", [](const Scenario& s) { return vectorToArray(s.scenario.robot->upperLimits()); })
      .def_property_readonly("queries", [](const Scenario& s) {
        py::list out;
        for (const auto& q : s.scenario.queries) out.append(py::make_tuple(vectorToArray(q.start), vectorToArray(q.goal)));
        return out;
      }, "list of (start, goal) arrays")
      .def_property_readonly("obstacles", [](const Scenario& s) {
        py::list names;
        for (const auto& o : s.scenario.environment->obstacles()) names.append(o.name);
        return names;
      }, "the obstacles' names in the file's order: obstacles[id - 1] is the one check() names by id")
      .def("check", [](const Scenario& s, const py::object& q) { return s.checker->check(s.point(q, "q")); }, py::arg("q"),
           "exact check (FCL primitives): 0 free, -1 joint limits, the lowest id (1-based index into obstacles) "
           "of a real obstacle hit, -2 self-collision")
      .def("is_valid", [](const Scenario& s, const py::object& q) { return s.checker->isValid(s.point(q, "q")); }, py::arg("q"))
      .def("clearance", [](const Scenario& s, const py::object& q) { return s.checker->clearance(s.point(q, "q")); },
           py::arg("q"), "distance of the robot to the nearest real obstacle (0 in contact), exact to 1e-6; "
           "geometric, so also outside the joint limits, where check() gives -1")
      .def("distance", [](const Scenario& s, const py::object& a, const py::object& b) {
        // The planners' metric (ConfigurationSpace::distance) on configurations scaled down by their
        // largest entry first, so finite ones far outside the limits give a finite distance where
        // one exists (1e200 overflowed to inf).
        const Eigen::VectorXd p = s.point(a, "a"), q = s.point(b, "b");
        const double m = std::max(p.cwiseAbs().maxCoeff(), q.cwiseAbs().maxCoeff());
        if (!(m > 0)) return 0.0;
        return m * (s.space.metricScale().array() * (p / m - q / m).array()).matrix().norm();
      }, py::arg("a"), py::arg("b"), "weighted joint metric (thesis eq. 4.3)")
      .def("__repr__", [](const Scenario& s) {
        return "<svmp.Scenario '" + s.scenario.name + "' dof=" + std::to_string(s.scenario.robot->dof()) + ">";
      });
  m.def("load_scenario", [](const py::object& path) { return Scenario(cspace::loadScenario(pathArgument(path, "path"))); },
        py::arg("path"),
        "Reads a scenario YAML file; a bad file raises svmp.ScenarioError (a ValueError) naming file, field and value.");

  py::class_<Plan>(m, "Plan", "One run of a planner: status, certified path and counters.")
      .def_readonly("planner", &Plan::planner)
      .def_readonly("seed", &Plan::seed)
      .def_readonly("status", &Plan::status, "solved, failed, timeout, invalid_start, invalid_goal, ...")
      .def_readonly("message", &Plan::message, "why, when not solved")
      .def_readonly("warnings", &Plan::warnings, "what the planner left out of its input (obstacles not sampled, why)")
      .def_readonly("solved", &Plan::solved, "solved and certified collision-free")
      .def_readonly("certified", &Plan::certified)
      .def_readonly("path", &Plan::path, "(n, dof) waypoints, start to goal; empty when not solved")
      .def_readonly("counters", &Plan::counters, "collision checks, local planner calls, ..., times (ms), path length")
      .def("__repr__", [](const Plan& p) {
        return "<svmp.Plan " + p.planner + " seed=" + std::to_string(p.seed) + " " + p.status + " waypoints=" +
               std::to_string(p.path.shape(0)) + ">";
      });
  m.def("plan", &plan, py::arg("scenario"), py::arg("planner"), py::arg("seed") = 1, py::arg("params") = py::dict(),
        py::arg("query") = 0, py::arg("checker") = "fcl", py::arg("time_limit") = 0.0, py::arg("threads") = 1,
        py::arg("simplify") = false,
        "Runs one registered planner on one query of the scenario as svmp-plan does (--seed, --set PLANNER.KEY=VALUE "
        "from params, --checker, --time-limit, --threads, --simplify: True shortcuts, 'svpp' follows an SVM, "
        "point robots); the path is certified collision-free.");
  m.def("planners", &planners::plannerNames, "registered planner names");
  ::pthread_atfork(nullptr, nullptr, &afterForkInChild);
}

}  // namespace svmp::python
