#pragma once
// The common interface of every planner the driver runs, the context they share (one scenario's
// space, collision checker and local planner, so counts are comparable), and the factory by name.
#include <memory>
#include <string>
#include <vector>

#include "cspace/collision_checker.hpp"
#include "cspace/configuration_space.hpp"
#include "cspace/motion_validator.hpp"
#include "cspace/parameters.hpp"
#include "cspace/scenario.hpp"
#include "planners/plan_result.hpp"

namespace svmp::planners {

struct PlanningContext {
  const cspace::ConfigurationSpace& space;
  const cspace::CollisionChecker& checker;
  const cspace::MotionValidator& validator;
  int threads = 1;
};

class Planner {
 public:
  virtual ~Planner() = default;
  virtual std::string name() const = 0;
  // Forgets everything learned (roadmap, models); the next solve starts from scratch.
  virtual void clear() = 0;
  // Answers one query; every random choice flows from `seed`. Counters and times cover this call.
  virtual PlanResult solve(const cspace::Query& query, std::uint64_t seed) = 0;
};

// Names: svmp, prm, local, ompl-prm, ompl-lazyprm, ompl-rrtconnect. Reads its parameters from `params`
// (throws cspace::ScenarioError naming field and value; unknown keys are errors too).
std::unique_ptr<Planner> makePlanner(const std::string& name, const PlanningContext& context,
                                     const cspace::ParameterSet& params);
std::vector<std::string> plannerNames();

// Shared by the roadmap planners: start and goal must be valid, else the status says which.
bool checkEndpoints(const PlanningContext& context, const cspace::Query& query, PlanResult& result);

}  // namespace svmp::planners
