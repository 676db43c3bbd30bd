#pragma once
// SVG pictures of a planning problem and of what a planner built (svmp-plan --svg DIR), in the
// style of the thesis' Figs 3.1-3.8, 4.1, 4.5 and 4.7: the configuration space of 2-DoF problems
// and the workspace of planar robots. Pictures are for looking at, not for measuring: the grids are
// coarse.
//
// Files are written whole or not at all (written to FILE.tmp, then renamed); a file that cannot be
// written throws std::runtime_error naming it. A null content.scenario throws
// std::invalid_argument.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "planners/obstacle_sampler.hpp"
#include "cspace/scenario/scenario.hpp"
#include "planners/risk_function.hpp"
#include "planners/roadmap.hpp"

namespace svmp::experiments {

// What to draw; pointers other than scenario may be null.
struct SvgContent {
  const cspace::Scenario* scenario = nullptr;  // robot, environment, queries
  const planners::ObstacleSamples* samples =
      nullptr;                                   // SVMP's obstacle samples (labels = obstacle ids)
  const planners::RiskFunction* risk = nullptr;  // decision boundaries F_k = 0
  const planners::Roadmap* roadmap = nullptr;    // milestones + edges
  const std::vector<Eigen::VectorXd>* path = nullptr;
  std::string title;
};

// 2-DoF configuration spaces: C-obstacle regions shaded from a 150 x 150 grid of collision checks
// (by a checker of its own, so the planner's counters are untouched), obstacle samples coloured by
// class with boundary samples circled, decision boundaries F_k = 0 (marching squares, one colour
// per class), milestones, roadmap edges, the path, start (square) and goal (diamond). Colours
// follow obstacle ids, the same in both pictures. Returns false, writing nothing, when dof != 2.
bool writeConfigurationSpaceSvg(const std::string& file, const SvgContent& content);

// Planar robots (planar arms, 2-D point robots): the obstacles projected on z = 0 (virtual ones
// dashed) and, for arms, `snapshots` poses evenly spaced by path length (start solid black, goal
// dashed grey as in thesis Fig 4.4, others light) with the trace of the tool tip; for point robots
// the path itself. Without a path the first query's start and goal are drawn. Returns false,
// writing nothing, when robot->workspaceDim() != 2.
bool writeWorkspaceSvg(const std::string& file, const SvgContent& content, int snapshots = 12);

}  // namespace svmp::experiments
