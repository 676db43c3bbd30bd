#pragma once
// `svmp-plan --check`: a scenario's summary (robot, dof, obstacles, each query's start and goal with
// their collision status and clearance, and the witness path when the file gives one).
#include <ostream>
#include <string>

#include "cspace/scenario/scenario.hpp"

namespace svmp::experiments {

// What a run and --check say of a self-collision pair the checker left out (droppedSelfCollisionPairs).
std::string droppedPairWarning(int a, int b);

// Prints the summary; returns false when a start, goal or witness segment is in collision.
bool printScenarioCheck(const cspace::Scenario& scenario, std::ostream& out);

// Throws cspace::ScenarioError naming the file, the field (start, goal, queries[i].start/goal or
// obstacles[i].sample), the configuration and what it hits when a query's start or goal is in
// collision (no planner can answer it) or an obstacle's `sample` misses that obstacle (it roots the
// obstacle's sampling tree); the drivers refuse both before running.
void requireValidConfigurations(const cspace::Scenario& scenario);

}  // namespace svmp::experiments
