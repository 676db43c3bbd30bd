#pragma once
// Verify and Repair (Das & Yip 2019, sec. IV-B): a path planned on a proxy collision checker (Fastron,
// cspace/fastron_checker.hpp) is verified with the exact checker, each waypoint checked and each segment
// proven free by the certified motion validator; every stretch that fails, from the last verified
// waypoint before it to the first valid waypoint after it, is replanned on the exact checker by the
// named planner (its own result certified) and spliced in. The result is certified or not returned.
// Planners use it through PlanningContext::repairer (planners/planner.hpp); roadmap planners prove
// their edges with the context's certifier instead (lazy repair).
// Thread safety: const; repairs may run concurrently only with distinct planners, which it makes per
// call.
#include <string>
#include <vector>

#include "cspace/scenario/parameters.hpp"
#include "planners/planner.hpp"

namespace svmp::planners {

struct RepairStats {
  int invalid_stretches = 0;  // stretches that failed verification (all repaired on success)
  std::uint64_t exact_checks = 0;  // exact collision checks of verification and repair
  double verify_ms = 0, repair_ms = 0;
};

class PathRepairer {
 public:
  // `exact` must have a certifier and outlive the repairer; with the certifier as its motion validator
  // too, a repair accepts only segments it proves (a sampled validator may pass a segment that clips a
  // corner, and the repair would fail certification). Repairs use `fallback_planner` when the planner
  // being repaired is not registered or builds a roadmap or model per call (svmp, prm, local, svpp),
  // and when the planner's own repair fails.
  PathRepairer(const PlanningContext& exact, std::string fallback_planner = "ompl-rrtconnect");

  // Verifies `path` (start and goal valid under the exact checker) and repairs its failing stretches
  // with a fresh `planner` on the exact context. True with `path` certified; false with `why` when a
  // stretch could not be repaired before `stop`.
  bool verifyAndRepair(std::vector<Eigen::VectorXd>& path, const std::string& planner, std::uint64_t seed,
                       const Termination& stop, RepairStats& stats, std::string& why) const;
  const PlanningContext& exactContext() const { return exact_; }

 private:
  const PlanningContext& exact_;
  std::string fallback_;
};

}  // namespace svmp::planners
