#pragma once
// The classical PRM the thesis compares against (Kavraki, Svestka, Latombe, Overmars, IEEE T-RA 1996;
// thesis ch. 3 intro and 4.2): N uniform random configurations, the collision-free ones become
// milestones, each connected to its k nearest milestones in other components by the same straight-line
// local planner SVMP uses; queries by A*. build() once, query() many times.
// Parameters (scenario `planners.prm`): the fields of PrmOptions, same names.
// Thread safety: as every Planner (planners/planner.hpp); OpenMP inside over the sample checks.
#include <optional>

#include "cspace/scenario/parameters.hpp"
#include "planners/nearest_neighbors.hpp"
#include "planners/planner.hpp"
#include "planners/roadmap.hpp"

namespace svmp::planners {

struct PrmOptions {
  int samples = 1000;  // uniform configurations drawn; the free ones become milestones
  int k = 10;

  static PrmOptions fromParameters(const cspace::ParameterSet& params);
  std::string validate() const;  // "" when usable
  bool operator==(const PrmOptions&) const = default;
};

class PrmPlanner final : public Planner {
 public:
  PrmPlanner(const PlanningContext& context, PrmOptions options);
  std::string name() const override { return "prm"; }
  void clear() override;
  PlannerView view() const override { return {nullptr, nullptr, &roadmap_}; }
  const Roadmap& roadmap() const { return roadmap_; }

 protected:
  bool triesStraightMotionFirst() const override { return true; }
  void buildRoadmap(std::uint64_t seed, const Termination& stop, PlanResult& result) override;
  void answer(const cspace::Query& query, std::uint64_t seed, const Termination& stop,
              PlanResult& result) override;

 private:
  PrmOptions options_;
  Roadmap roadmap_;
  Roadmap with_query_;  // roadmap_ plus a query's endpoints; assigned anew per query, keeping its allocations
  std::optional<NearestNeighbors> nn_;
};

}  // namespace svmp::planners
