#pragma once
// The OMPL bridge (Sucan, Moll, Kavraki, IEEE RAM 2012): our collision checker as OMPL's state validity
// checker and our straight-line validator as its motion validator, so OMPL's PRM (Kavraki et al. 1996),
// LazyPRM (Bohlin, Kavraki 2000) and RRTConnect (Kuffner, LaValle 2000) run on the same scenarios with
// the same checking resolution and counters. OMPL works on coordinates scaled by sqrt(w), where its
// Euclidean distance is the weighted metric of thesis eq. 4.3.
// Parameters (scenario `planners.ompl-*`): time_limit (s, default 10), range (RRTConnect, 0 = OMPL's
// default), k (PRM neighbours, 0 = OMPL's default).
// Determinism: sampling uses our seeded generator, but OMPL's PRM interleaves growth and expansion by
// wall time and checks for solutions in a second thread, so its runs are not exactly repeatable.
#include <memory>

#include "planners/planner.hpp"

namespace svmp::planners {

std::unique_ptr<Planner> makeOmplPlanner(const std::string& name, const PlanningContext& context,
                                         const cspace::ParameterSet& params);

}  // namespace svmp::planners
