#include "planners/planner_registry.hpp"

#include <map>
#include <stdexcept>

namespace svmp::planners {
namespace {

// A function-local static: built on first use, whatever the order of static initialisers.
std::map<std::string, PlannerFactory>& registry() {
  static std::map<std::string, PlannerFactory> factories;
  return factories;
}

}  // namespace

bool registerPlanner(const std::string& name, PlannerFactory factory) {
  if (!registry().emplace(name, std::move(factory)).second)
    throw std::logic_error("planner '" + name + "' registered twice");
  return true;
}

std::vector<std::string> plannerNames() {
  std::vector<std::string> names;
  for (const auto& [name, factory] : registry()) names.push_back(name);
  return names;
}

std::string unknownPlanner(const std::string& name) {
  std::string known;
  for (const auto& n : plannerNames()) known += (known.empty() ? "" : ", ") + n;
  return "unknown planner '" + name + "' (known: " + known + ")";
}

std::unique_ptr<Planner> makePlanner(const std::string& name, const PlanningContext& context,
                                     const cspace::ParameterSet& params) {
  const auto it = registry().find(name);
  if (it == registry().end()) throw cspace::ScenarioError(unknownPlanner(name));
  auto planner = it->second(context, params);
  params.requireAllUsed();
  return planner;
}

}  // namespace svmp::planners
