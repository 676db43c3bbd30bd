#include "planners/planner.hpp"

#include "planners/local_planner.hpp"
#include "planners/prm_planner.hpp"
#include "planners/svmp_planner.hpp"
#ifdef SVMP_WITH_OMPL
#include "planners/ompl_bridge.hpp"
#endif

namespace svmp::planners {

const char* planStatusName(PlanStatus status) {
  switch (status) {
    case PlanStatus::kSolved: return "solved";
    case PlanStatus::kFailed: return "failed";
    case PlanStatus::kTimeout: return "timeout";
    case PlanStatus::kInvalidStart: return "invalid_start";
    case PlanStatus::kInvalidGoal: return "invalid_goal";
    case PlanStatus::kInvalidInput: return "invalid_input";
    case PlanStatus::kLocalMinimum: return "local_minimum";
  }
  return "?";
}

bool checkEndpoints(const PlanningContext& context, const cspace::Query& query, PlanResult& result) {
  if (query.start.size() != context.space.dim() || query.goal.size() != context.space.dim()) {
    result.status = PlanStatus::kInvalidInput;
    result.message = "query size differs from the configuration space's dimension";
    return false;
  }
  if (const int hit = context.checker.check(query.start); hit != cspace::kFree) {
    result.status = PlanStatus::kInvalidStart;
    result.message = "start is in collision (hit " + std::to_string(hit) + ")";
    return false;
  }
  if (const int hit = context.checker.check(query.goal); hit != cspace::kFree) {
    result.status = PlanStatus::kInvalidGoal;
    result.message = "goal is in collision (hit " + std::to_string(hit) + ")";
    return false;
  }
  return true;
}

std::vector<std::string> plannerNames() {
  std::vector<std::string> names = {"svmp", "prm", "local"};
#ifdef SVMP_WITH_OMPL
  for (const char* n : {"ompl-prm", "ompl-lazyprm", "ompl-rrtconnect"}) names.push_back(n);
#endif
  return names;
}

std::unique_ptr<Planner> makePlanner(const std::string& name, const PlanningContext& context,
                                     const cspace::ParameterSet& params) {
  std::unique_ptr<Planner> planner;
  if (name == "svmp") {
    SvmpOptions o;
    o.sigma = params.getDouble("sigma", o.sigma, 1e-9);
    o.C = params.getDouble("C", o.C, 1e-9);
    o.step = params.getDouble("step", o.step, 1e-9);
    o.samples_per_tree = static_cast<int>(params.getInt("samples_per_tree", o.samples_per_tree, 1, 1000000));
    o.k = static_cast<int>(params.getInt("k", o.k, 1, 10000));
    o.eps = params.getDouble("eps", o.eps, 1e-15, 1);
    o.cache_mb = params.getDouble("cache_mb", o.cache_mb, 1, 1e6);
    o.truncated = params.getBool("truncated", o.truncated);
    o.descent.tolerance = params.getDouble("descent_tolerance", o.descent.tolerance, 0, 1e6);
    o.descent.max_step = params.getDouble("descent_step", o.sigma, 1e-12);
    o.descent.max_iterations = static_cast<int>(params.getInt("descent_iterations", o.descent.max_iterations, 1, 1000000));
    o.duplicate_radius = params.getDouble("duplicate_radius", 0.5 * o.step, 0);
    o.repair_rounds = static_cast<int>(params.getInt("repair_rounds", o.repair_rounds, 0, 1000));
    o.repair_samples = static_cast<int>(params.getInt("repair_samples", o.repair_samples, 2, 1000000));
    o.centre_in_passage = params.getBool("centre_in_passage", o.centre_in_passage);
    o.sample_self_collision = params.getBool("sample_self_collision", o.sample_self_collision);
    planner = std::make_unique<SvmpPlanner>(context, o);
  } else if (name == "local") {
    LocalPlannerOptions o;
    o.sigma = params.getDouble("sigma", o.sigma, 1e-9);
    o.C = params.getDouble("C", o.C, 1e-9);
    o.mu = params.getDouble("mu", o.mu, 0);
    o.step = params.getDouble("step", o.step, 1e-9);
    o.boundary_tolerance = params.getDouble("boundary_tolerance", o.boundary_tolerance, 0);
    o.eps = params.getDouble("eps", o.eps, 1e-15, 1);
    o.labelling = params.getString("labelling", "balanced", {"balanced", "random"}) == "random"
                      ? LabellingMethod::kRandom
                      : LabellingMethod::kBalanced;
    o.sampling.link_resolution = params.getDouble("link_resolution", o.sampling.link_resolution, 1e-6);
    o.sampling.obstacle_resolution = params.getDouble("obstacle_resolution", o.sampling.obstacle_resolution, 1e-6);
    o.sampling.boundary_resolution = params.getDouble("boundary_resolution", o.sampling.boundary_resolution, 1e-6);
    o.sampling.max_samples = static_cast<int>(params.getInt("max_samples", o.sampling.max_samples, 2, 1000000));
    o.max_iterations = static_cast<int>(params.getInt("max_iterations", o.max_iterations, 1, 100000000));
    o.stall_iterations = static_cast<int>(params.getInt("stall_iterations", o.stall_iterations, 1, 100000000));
    planner = std::make_unique<LocalPlanner>(context, o);
  } else if (name == "prm") {
    PrmOptions o;
    o.samples = static_cast<int>(params.getInt("samples", o.samples, 1, 100000000));
    o.k = static_cast<int>(params.getInt("k", o.k, 1, 10000));
    planner = std::make_unique<PrmPlanner>(context, o);
#ifdef SVMP_WITH_OMPL
  } else if (name.rfind("ompl-", 0) == 0) {
    planner = makeOmplPlanner(name, context, params);
#endif
  } else {
    std::string known;
    for (const auto& n : plannerNames()) known += (known.empty() ? "" : ", ") + n;
    throw cspace::ScenarioError("unknown planner '" + name + "' (known: " + known + ")");
  }
  params.requireAllUsed();
  return planner;
}

}  // namespace svmp::planners
