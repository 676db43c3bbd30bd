#pragma once
// Planners by name. Each planner registers itself in its own source file with SVMP_REGISTER_PLANNER, so
// adding one touches no other file (the driver, the OMPL planners and the tests find it here). Each
// factory reads its parameters through its Options::fromParameters (bounds, defaults in one place) and
// throws cspace::ScenarioError naming field and value; keys it did not read are errors too.
//
// Thread safety: registration happens during static initialisation; lookups may run concurrently
// afterwards.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "cspace/scenario/parameters.hpp"
#include "planners/planner.hpp"

namespace svmp::planners {

using PlannerFactory =
    std::function<std::unique_ptr<Planner>(const PlanningContext&, const cspace::ParameterSet&)>;

// Returns true (for use in a static initialiser); throws std::logic_error when the name is taken.
bool registerPlanner(const std::string& name, PlannerFactory factory);

// Throws cspace::ScenarioError for an unknown name (listing the known ones) or a bad parameter.
std::unique_ptr<Planner> makePlanner(const std::string& name, const PlanningContext& context,
                                     const cspace::ParameterSet& params);
// Registered names, sorted.
std::vector<std::string> plannerNames();
// "unknown planner 'NAME' (known: ...)", the message makePlanner throws for a name not registered.
std::string unknownPlanner(const std::string& name);

}  // namespace svmp::planners

#define SVMP_PLANNER_CONCAT_(a, b) a##b
#define SVMP_PLANNER_CONCAT(a, b) SVMP_PLANNER_CONCAT_(a, b)
// SVMP_REGISTER_PLANNER("name", factory) at namespace scope of one source file.
#define SVMP_REGISTER_PLANNER(name, ...)                                                   \
  [[maybe_unused]] static const bool SVMP_PLANNER_CONCAT(svmp_planner_registered_, __LINE__) = \
      ::svmp::planners::registerPlanner(name, __VA_ARGS__)
