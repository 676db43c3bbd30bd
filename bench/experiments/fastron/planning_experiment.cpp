#include "bench/experiments/fastron/planning_experiment.hpp"

#include <iomanip>
#include <tuple>
#include <map>
#include <ostream>
#include <sstream>

#include "bench/experiments/output_text.hpp"
#include "cspace/certified_motion_validator.hpp"
#include "cspace/motion_validator.hpp"
#include "planners/path_simplifier.hpp"
#include "planners/planner_registry.hpp"
#include "planners/verify_repair.hpp"

namespace svmp::experiments::fastron {
namespace {

// One checker's context for one obstacle position.
struct CheckerWorld {
  std::string name;
  const cspace::ValidityChecker* checker;
  std::unique_ptr<cspace::MotionValidator> validator;  // null: the exact one
};

}  // namespace

PlanningResults runPlanningExperiment(const cspace::Scenario& scenario, const PlanningExperimentOptions& options,
                                      std::ostream& log) {
  if (scenario.queries.empty() || scenario.environment->obstacles().empty() ||
      scenario.environment->obstacles().front().shape.kind != robots::ShapeKind::kBox)
    throw cspace::ScenarioError(scenario.path + ": the planning experiment needs a query and a box obstacle first");
  const cspace::Query& query = scenario.queries.front();
  const cspace::Obstacle& moving = scenario.environment->obstacles().front();
  const robots::Shape& shape = moving.shape;
  if (!MovingBox::inRegion(options.box, shape.pose.translation())) {
    std::ostringstream msg;
    const Eigen::Vector3d& c = shape.pose.translation();
    msg << scenario.path << ": obstacle '" << moving.name << "' at (" << c.x() << ", " << c.y() << ", " << c.z()
        << "): the planning experiment moves the first obstacle in a ring " << options.box.ring_inner << "-"
        << options.box.ring_outer << " m from the base's z axis at heights " << options.box.z_low << "-"
        << options.box.z_high << " m (an arm of the Panda's size); it must start there";
    throw cspace::ScenarioError(msg.str());
  }
  const std::vector<cspace::Obstacle> fixed(scenario.environment->obstacles().begin() + 1,
                                            scenario.environment->obstacles().end());
  const cspace::ConfigurationSpace space = scenario.makeSpace();
  PlanningResults results;
  std::map<std::pair<std::string, std::string>, PlannerCheckerRuns> rows;
  const std::vector<std::string> checkers = {"fcl", "fastron-fk", "fastron-rbf"};
  for (int trial = 0; trial < options.trials; ++trial) {
    std::mt19937_64 rng(options.seed + 1000003ULL * trial);
    MovingBox box(options.box, shape.dims, shape.pose);
    cspace::FastronChecker fk(scenario.robot, options.fk), rbf(scenario.robot, options.rbf);
    for (int move = 0; move <= options.moves; ++move) {
      std::unique_ptr<cspace::CollisionChecker> exact;
      for (int attempt = 0;; ++attempt) {
        MovingBox moved = box;
        if (move > 0) moved.move(rng);
        exact = moved.checker(scenario, fixed);
        if (exact->isValid(query.start) && exact->isValid(query.goal)) {
          box = moved;
          break;
        }
        if (attempt == 100)
          throw std::runtime_error("no move of the box in 100 kept the query's start and goal free (it moves in a ring "
                                   "0.35-0.75 m round the base, for an arm of the Panda's size)");
      }
      const std::vector<Eigen::VectorXd> ends = {query.start, query.goal};
      for (auto [proxy, times, sizes] : {std::tuple{&fk, &results.fk_update_ms, &results.fk_support},
                                         std::tuple{&rbf, &results.rbf_update_ms, &results.rbf_support}}) {
        const auto s = move == 0 ? proxy->train(*exact, rng(), ends) : proxy->update(*exact, rng(), ends);
        times->push_back(s.label_ms + s.learn_ms);
        sizes->push_back(s.train.support);
      }
      ++results.positions;
      const cspace::DiscreteMotionValidator exact_validator(*exact, space, scenario.resolution);
      const cspace::CertifiedMotionValidator certifier(*exact, space, scenario.resolution);
      const planners::PlanningContext repair_context{space, *exact, certifier, 1, &certifier};
      const planners::PathRepairer repairer(repair_context);
      std::vector<CheckerWorld> worlds;
      worlds.push_back({"fcl", exact.get(), nullptr});
      for (auto [name, proxy] : {std::pair{"fastron-fk", &fk}, std::pair{"fastron-rbf", &rbf}})
        worlds.push_back({name, proxy, std::make_unique<cspace::DiscreteMotionValidator>(*proxy, space, scenario.resolution)});
      for (const auto& planner_name : options.planners) {
        for (const auto& w : worlds) {
          const cspace::MotionValidator& validator =
              w.validator ? *w.validator : static_cast<const cspace::MotionValidator&>(exact_validator);
          const planners::PlanningContext context{space, *w.checker, validator, 1, &certifier, &repairer};
          auto planner = planners::makePlanner(planner_name, context, scenario.paramsFor(planner_name));
          PlannerCheckerRuns& row = rows[{planner_name, w.name}];
          row.planner = planner_name, row.checker = w.name;
          for (int p = 0; p < options.plans_per_move; ++p) {
            const std::uint64_t exact0 = exact->collisionChecks();
            const auto t0 = planners::Clock::now();
            const auto r = planner->solve(query, rng(), planners::Termination::after(options.time_limit));
            if (r.status == planners::PlanStatus::kInvalidInput)  // the robot is not the planner's
              throw std::invalid_argument(planner_name + ": " + r.message);
            row.time_ms.push_back(planners::msSince(t0) - r.counting_ms);
            ++row.runs;
            row.proxy_checks.push_back(w.validator ? double(r.collision_checks) : 0.0);
            row.exact_checks.push_back(double(exact->collisionChecks() - exact0));
            if (!r.solved() || !r.certified) continue;
            ++row.solved;
            row.repaired_stretches.push_back(r.repaired_stretches);
            row.repair_ms.push_back(r.times.certify_ms);
            row.length.push_back(planners::pathLength(r.path, space));
          }
        }
      }
    }
    log << "planning trial " << trial + 1 << "/" << options.trials << " done\n";
  }
  for (const auto& planner : options.planners)
    for (const auto& c : checkers) results.rows.push_back(rows[{planner, c}]);
  return results;
}

void printPlanningTable(const PlanningResults& r, std::ostream& out) {
  out << "\nFig 6: planning with verify and repair, " << r.positions
      << " obstacle positions; time = wall time per query (verify and repair included), mean ± std [median]\n"
      << "model updates: fastron-fk " << meanStd(statsOf(r.fk_update_ms), 1) << " ms ("
      << meanStd(statsOf(r.fk_support), 0) << " support points), fastron-rbf " << meanStd(statsOf(r.rbf_update_ms), 1)
      << " ms (" << meanStd(statsOf(r.rbf_support), 0) << ")\n";
  out << pad("planner", 22) << pad("checker", 13) << pad("solved", 11) << pad("time ms", 26) << pad("vs fcl", 8)
      << pad("verify+repair ms", 18) << pad("repaired", 10) << pad("exact checks", 16) << "path length\n";
  std::map<std::string, double> fcl_median;
  for (const auto& row : r.rows)
    if (row.checker == "fcl") fcl_median[row.planner] = statsOf(row.time_ms).median;
  for (const auto& row : r.rows) {
    const Stats t = statsOf(row.time_ms);
    std::ostringstream time, ratio;
    time << meanStd(t, 1) << " [" << std::fixed << std::setprecision(1) << t.median << "]";
    ratio << std::fixed << std::setprecision(2) << fcl_median[row.planner] / std::max(t.median, 1e-9) << "x";
    out << pad(row.planner, 22) << pad(row.checker, 13)
        << pad(std::to_string(row.solved) + "/" + std::to_string(row.runs), 11) << pad(time.str(), 26)
        << pad(ratio.str(), 8) << pad(meanStd(statsOf(row.repair_ms), 2), 18)
        << pad(meanStd(statsOf(row.repaired_stretches), 2), 10) << pad(meanStd(statsOf(row.exact_checks), 0), 16)
        << meanStd(statsOf(row.length), 2) << "\n";
  }
}

std::string planningJson(const PlanningResults& r) {
  std::ostringstream o;
  o << std::setprecision(10) << "{\"positions\": " << r.positions << ", \"fastron_fk_update_ms\": "
    << jsonStats(statsOf(r.fk_update_ms)) << ", \"fastron_rbf_update_ms\": " << jsonStats(statsOf(r.rbf_update_ms))
    << ", \"fastron_fk_support\": " << jsonStats(statsOf(r.fk_support))
    << ", \"fastron_rbf_support\": " << jsonStats(statsOf(r.rbf_support)) << ", \"runs\": [";
  for (size_t i = 0; i < r.rows.size(); ++i) {
    const auto& row = r.rows[i];
    o << (i ? ", " : "") << "{\"planner\": \"" << row.planner << "\", \"checker\": \"" << row.checker
      << "\", \"runs\": " << row.runs << ", \"solved\": " << row.solved << ", \"time_ms\": " << jsonStats(statsOf(row.time_ms))
      << ", \"verify_repair_ms\": " << jsonStats(statsOf(row.repair_ms))
      << ", \"repaired_stretches\": " << jsonStats(statsOf(row.repaired_stretches))
      << ", \"proxy_checks\": " << jsonStats(statsOf(row.proxy_checks))
      << ", \"exact_checks\": " << jsonStats(statsOf(row.exact_checks)) << ", \"path_length\": " << jsonStats(statsOf(row.length))
      << "}";
  }
  o << "]}";
  return o.str();
}

}  // namespace svmp::experiments::fastron
