#pragma once
// The classical PRM the thesis compares against (Kavraki, Svestka, Latombe, Overmars, IEEE T-RA 1996;
// thesis ch. 3 intro and 4.2): N uniform random configurations, the collision-free ones become
// milestones, each connected to its k nearest milestones in other components by the same straight-line
// local planner SVMP uses; queries by A*. Parameters (scenario `planners.prm`): samples, k.
#include "planners/planner.hpp"
#include "planners/roadmap.hpp"

namespace svmp::planners {

struct PrmOptions {
  int samples = 1000;  // uniform configurations drawn; the free ones become milestones
  int k = 10;
};

class PrmPlanner final : public Planner {
 public:
  PrmPlanner(const PlanningContext& context, PrmOptions options);
  std::string name() const override { return "prm"; }
  void clear() override { roadmap_.clear(); }
  PlanResult solve(const cspace::Query& query, std::uint64_t seed) override;
  const Roadmap& roadmap() const { return roadmap_; }

 private:
  PlanningContext context_;
  PrmOptions options_;
  Roadmap roadmap_;
};

}  // namespace svmp::planners
