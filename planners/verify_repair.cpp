#include "planners/verify_repair.hpp"

#include <algorithm>
#include <stdexcept>

#include "planners/planner_registry.hpp"

namespace svmp::planners {

PathRepairer::PathRepairer(const PlanningContext& exact, std::string fallback_planner)
    : exact_(exact), fallback_(std::move(fallback_planner)) {
  if (!exact.certifier) throw std::invalid_argument("PathRepairer: the exact context needs a certifier");
}

bool PathRepairer::verifyAndRepair(std::vector<Eigen::VectorXd>& path, const std::string& planner,
                                   std::uint64_t seed, const Termination& stop, RepairStats& stats,
                                   std::string& why) const {
  const std::uint64_t checks0 = exact_.checker.collisionChecks();
  const auto t0 = Clock::now();
  // Planners that build a roadmap or a model per call are no repairers of a short stretch.
  const bool roadmap = planner == "svmp" || planner == "prm" || planner == "local" || planner == "svpp";
  const std::vector<std::string> names = plannerNames();
  const std::string repairer =
      !roadmap && std::find(names.begin(), names.end(), planner) != names.end() ? planner : fallback_;
  std::vector<Eigen::VectorXd> out;
  bool ok = !path.empty();
  if (ok) out.push_back(path.front());
  double repair_ms = 0;
  for (size_t i = 0; ok && i + 1 < path.size();) {
    if (exact_.checker.isValid(path[i + 1]) && exact_.certifier->isValid(path[i], path[i + 1])) {
      out.push_back(path[++i]);
      continue;
    }
    size_t j = i + 1;
    while (j + 1 < path.size() && !exact_.checker.isValid(path[j])) ++j;
    ++stats.invalid_stretches;
    const auto r0 = Clock::now();
    const cspace::Query stretch{path[i], path[j], {}};
    auto sub = makePlanner(repairer, exact_, cspace::ParameterSet())->solve(stretch, seed + stats.invalid_stretches, stop);
    if (!sub.solved() && repairer != fallback_)
      sub = makePlanner(fallback_, exact_, cspace::ParameterSet())->solve(stretch, seed + stats.invalid_stretches, stop);
    repair_ms += msSince(r0);
    if (!sub.solved()) {
      why = "repair of waypoints " + std::to_string(i) + " to " + std::to_string(j) + " with " + repairer +
            (repairer != fallback_ ? " and " + fallback_ : "") + " failed: " + sub.message;
      ok = false;
      break;
    }
    out.insert(out.end(), sub.path.begin() + 1, sub.path.end());
    i = j;
  }
  stats.repair_ms += repair_ms;
  stats.verify_ms += msSince(t0) - repair_ms;
  stats.exact_checks += exact_.checker.collisionChecks() - checks0;
  if (ok) path = std::move(out);
  return ok;
}

}  // namespace svmp::planners
