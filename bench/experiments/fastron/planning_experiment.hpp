#pragma once
// Das & Yip 2019, sec. IV-B (Fig 6): sampling-based planners with FCL, Fastron FK and Fastron RBF on a
// box the arm must go around (the scenario's obstacle), moved between plans. Per trial the box starts
// where the scenario puts it and moves `moves` times (a move that would put the start or goal in
// collision is drawn again); after each move both models are updated (active learning, the query's
// end points among the training points) and every planner plans `plans_per_move` times with each
// checker. With a proxy every path is verified on FCL and its invalid stretches replanned there
// (planners/verify_repair.hpp); svmp and prm prove their roadmap edges with FCL instead. With FCL as
// well, a path whose segment clips an obstacle between the sampled checks is repaired, not dropped,
// so every checker gets the same treatment. A run counts
// as solved only when its path is certified. Times are wall time of the whole query, verify and
// repair included; model updates are timed apart.
#include <iosfwd>
#include <string>
#include <vector>

#include "bench/experiments/fastron/moving_box.hpp"
#include "cspace/fastron_checker.hpp"

namespace svmp::experiments::fastron {

struct PlanningExperimentOptions {
  int trials = 50, moves = 30, plans_per_move = 10;
  std::uint64_t seed = 1;
  double time_limit = 10;  // s per plan
  std::vector<std::string> planners = {"ompl-rrt", "ompl-rrtconnect", "ompl-sbl", "ompl-rrtstar",
                                       "ompl-fmt", "ompl-informedrrtstar", "svmp", "prm"};
  cspace::FastronCheckerOptions fk = cspace::FastronCheckerOptions::defaults(cspace::FastronFeatures::kControlPoints);
  cspace::FastronCheckerOptions rbf = cspace::FastronCheckerOptions::defaults(cspace::FastronFeatures::kJoints);
  MovingBoxOptions box;
};

struct PlannerCheckerRuns {
  std::string planner, checker;
  int runs = 0, solved = 0;
  std::vector<double> time_ms, repair_ms, length;  // time of every run; repair and length of solved ones
  std::vector<double> repaired_stretches, proxy_checks, exact_checks;
};

struct PlanningResults {
  std::vector<PlannerCheckerRuns> rows;
  std::vector<double> fk_update_ms, rbf_update_ms;
  std::vector<double> fk_support, rbf_support;  // model sizes after each training or update
  int positions = 0;  // obstacle positions planned on
};

PlanningResults runPlanningExperiment(const cspace::Scenario& scenario, const PlanningExperimentOptions& options,
                                      std::ostream& log);
void printPlanningTable(const PlanningResults& results, std::ostream& out);
std::string planningJson(const PlanningResults& results);

}  // namespace svmp::experiments::fastron
