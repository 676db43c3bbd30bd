// The OMPL bridge (Sucan, Moll, Kavraki, IEEE RAM 2012): our collision checker as OMPL's state validity
// checker and our straight-line validator as its motion validator, so OMPL's PRM (Kavraki et al. 1996),
// LazyPRM (Bohlin, Kavraki 2000), RRTConnect (Kuffner, LaValle 2000), RRT (LaValle 1998), SBL (Sanchez,
// Latombe 2003), RRT* (Karaman, Frazzoli 2011), FMT* (Janson et al. 2015) and Informed RRT* (Gammell et
// al. 2014) run on the same scenarios with the same checking resolution and counters. The optimizing
// planners (RRT*, FMT*, Informed RRT*) stop at their first solution by default (path length objective
// with an infinite cost threshold), as in Das & Yip 2019 sec. IV-B. OMPL works on coordinates scaled
// by sqrt(w), where its Euclidean distance is the weighted metric of thesis eq. 4.3.
// Parameters (scenario `planners.ompl-*`): time_limit (s; 0, the default: the run's own limit, or 10 s
// when the run has none, so OMPL never runs unbounded and --time-limit 30 gives it 30 s), range (the tree planners, 0 =
// OMPL's default), k (PRM neighbours, 0 = OMPL's default), first_solution (optimizing planners, default
// true; false runs them until the time limit).
// Determinism: sampling uses our seeded generator and each planner's own generator is seeded from the
// run's seed, but OMPL's PRM interleaves growth and expansion by wall time and checks for solutions in
// a second thread, so it is not exactly repeatable. Informed RRT* repeats up to its first solution
// (its sampler draws through the space's default sampler, ours: state_bridge.cpp), so stopped there
// it takes RRT*'s checks and path (its tree pruned at that solution); its informed draws after one
// come from OMPL's per-process generator.
// The planners register themselves as ompl-prm, ompl-lazyprm, ompl-rrtconnect, ompl-rrt, ompl-sbl,
// ompl-rrtstar, ompl-fmt and ompl-informedrrtstar (planners/planner_registry.hpp); nothing else is
// exported. The state space, checker and validator are planners/ompl/state_bridge.hpp's.

#include "planners/planner_registry.hpp"
#include "planners/ompl/state_bridge.hpp"

#include <ompl/base/SpaceInformation.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/planners/prm/LazyPRM.h>
#include <ompl/geometric/planners/prm/PRM.h>
#include <ompl/base/objectives/PathLengthOptimizationObjective.h>
#include <ompl/geometric/planners/fmt/FMT.h>
#include <ompl/geometric/planners/rrt/InformedRRTstar.h>
#include <ompl/geometric/planners/rrt/RRT.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/geometric/planners/rrt/RRTstar.h>
#include <ompl/geometric/planners/sbl/SBL.h>
#include <ompl/util/Console.h>

#include <chrono>
#include <limits>
#include <random>

namespace svmp::planners {
namespace {

namespace ob = ompl::base;
namespace og = ompl::geometric;

// An OMPL planner whose own generator (goal bias, tree and cell choices) follows the run's seed:
// OMPL seeds each RNG from one per-process sequence, so runs would depend on what ran before.
template <class P>
class Seeded final : public P {
 public:
  Seeded(const ob::SpaceInformationPtr& si, std::uint_fast32_t seed) : P(si) {
    this->rng_.setLocalSeed(seed);
  }
};

// Uniform sampling from our seeded generator, so OMPL's samples follow the run's seed.
class SeededSampler final : public ob::StateSampler {
 public:
  SeededSampler(const ob::StateSpace* space, std::uint64_t seed) : ob::StateSampler(space), rng_(seed) {}
  void sampleUniform(ob::State* state) override {
    const auto& bounds = space_->as<ob::RealVectorStateSpace>()->getBounds();
    auto* v = state->as<ob::RealVectorStateSpace::StateType>();
    for (size_t i = 0; i < bounds.low.size(); ++i)
      v->values[i] = std::uniform_real_distribution<double>(bounds.low[i], bounds.high[i])(rng_);
  }
  void sampleUniformNear(ob::State* state, const ob::State* near, double distance) override {
    const auto& bounds = space_->as<ob::RealVectorStateSpace>()->getBounds();
    auto* v = state->as<ob::RealVectorStateSpace::StateType>();
    const auto* c = near->as<ob::RealVectorStateSpace::StateType>();
    for (size_t i = 0; i < bounds.low.size(); ++i)
      v->values[i] = std::clamp(c->values[i] + std::uniform_real_distribution<double>(-distance, distance)(rng_),
                                bounds.low[i], bounds.high[i]);
  }
  void sampleGaussian(ob::State* state, const ob::State* mean, double stddev) override {
    const auto& bounds = space_->as<ob::RealVectorStateSpace>()->getBounds();
    auto* v = state->as<ob::RealVectorStateSpace::StateType>();
    const auto* c = mean->as<ob::RealVectorStateSpace::StateType>();
    for (size_t i = 0; i < bounds.low.size(); ++i)
      v->values[i] = std::clamp(c->values[i] + std::normal_distribution<double>(0, stddev)(rng_),
                                bounds.low[i], bounds.high[i]);
  }

 private:
  std::mt19937_64 rng_;
};

struct OmplOptions {
  double time_limit = 0;  // s; 0: the run's limit, or kDefaultTimeLimit without one
  static constexpr double kDefaultTimeLimit = 10;
  double range = 0;        // the tree planners' range; 0: OMPL's default
  int k = 0;               // PRM neighbours; 0: OMPL's default
  bool first_solution = true;  // optimizing planners stop at their first solution

  static OmplOptions fromParameters(const cspace::ParameterSet& params) {
    OmplOptions o;
    o.time_limit = params.getDouble("time_limit", o.time_limit, 0.0, 1e6);
    o.range = params.getDouble("range", o.range, 0.0, 1e6);
    o.k = static_cast<int>(params.getInt("k", o.k, 0, 10000));
    o.first_solution = params.getBool("first_solution", o.first_solution);
    return o;
  }
};

// Every query starts OMPL afresh: the planners are OMPL's, with their own roadmaps; nothing to build.
class OmplPlanner final : public Planner {
 public:
  OmplPlanner(std::string name, const PlanningContext& context, OmplOptions options)
      : Planner(context), name_(std::move(name)), options_(options) {}
  std::string name() const override { return name_; }
  void clear() override { forgetBuild(); }

 protected:
  void buildRoadmap(std::uint64_t, const Termination&, PlanResult& result) override {
    result.status = PlanStatus::kSolved;
  }

  void answer(const cspace::Query& query, std::uint64_t seed, const Termination& stop,
              PlanResult& result) override {
    const Eigen::VectorXd& scale = context_.space.metricScale();
    std::uint64_t sampler_seed = seed;
    const ob::SpaceInformationPtr si =
        ompl_planners::makeSpaceInformation(context_, nullptr, [sampler_seed](const ob::StateSpace* s) mutable {
          return std::make_shared<SeededSampler>(s, sampler_seed++ * 0x9E3779B97F4A7C15ULL + 1);
        });
    const ob::StateSpacePtr& space = si->getStateSpace();
    auto pdef = std::make_shared<ob::ProblemDefinition>(si);
    ob::ScopedState<> start(space), goal(space);
    ompl_planners::toState(query.start, scale, start.get());
    ompl_planners::toState(query.goal, scale, goal.get());
    pdef->setStartAndGoalStates(start, goal);
    const bool optimizing = name_ == "ompl-rrtstar" || name_ == "ompl-fmt" || name_ == "ompl-informedrrtstar";
    if (optimizing && options_.first_solution) {
      auto objective = std::make_shared<ob::PathLengthOptimizationObjective>(si);
      objective->setCostThreshold(ob::Cost(std::numeric_limits<double>::infinity()));
      pdef->setOptimizationObjective(objective);
    }
    const ob::PlannerPtr planner = makeOmplPlanner(si, seed);
    planner->setProblemDefinition(pdef);
    planner->setup();
    const auto t0 = Clock::now();
    const double own_limit = options_.time_limit > 0 ? options_.time_limit
                             : stop.hasDeadline()   ? std::numeric_limits<double>::infinity()
                                                    : OmplOptions::kDefaultTimeLimit;
    const Termination until = Termination::when([&stop] { return stop(); }, Termination::after(own_limit));
    const cspace::MotionStopScope motion_stop(until.asFunction());  // OMPL's own limit stops a long segment too
    const ob::PlannerStatus status = planner->solve(ob::PlannerTerminationCondition([&until] { return until(); }));
    result.times.query_ms += msSince(t0);
    // Counting copies the roadmap out (1.4 s for ompl-prm's 69k milestones after a 2 s timeout):
    // not for a run its limit ended.
    if (status == ob::PlannerStatus::EXACT_SOLUTION || !until()) {
      const auto t1 = Clock::now();
      ob::PlannerData data(si);
      planner->getPlannerData(data);
      result.milestones = data.numVertices();
      result.roadmap_edges = data.numEdges();
      result.counting_ms += msSince(t1);
    }
    if (status == ob::PlannerStatus::EXACT_SOLUTION) {
      auto* path = pdef->getSolutionPath()->as<og::PathGeometric>();
      for (size_t i = 0; i < path->getStateCount(); ++i)
        result.path.push_back(ompl_planners::toConfiguration(path->getState(i), context_.space));
      // The query's own ends, not their round trip through OMPL's scaled states (one unit in the last
      // place apart where the metric weights are not 1).
      result.path.front() = query.start;
      result.path.back() = query.goal;
      result.status = PlanStatus::kSolved;
      certify(result, seed, until);  // a repair of its path keeps within the planner's own limit
    } else {
      result.status = status == ob::PlannerStatus::TIMEOUT || status == ob::PlannerStatus::APPROXIMATE_SOLUTION
                          ? PlanStatus::kTimeout
                          : PlanStatus::kFailed;
      // RRTConnect's nearest pair when the limit ends it is an "approximate solution": not one.
      result.message = result.status == PlanStatus::kTimeout
                           ? "time limit reached without a solution (OMPL: " + status.asString() + ")"
                           : std::string("OMPL: ") + status.asString();
      // The query's ends are free on the exact checker (checkEndpoints): a learned proxy called them not.
      if (context_.repairer && (status == ob::PlannerStatus::INVALID_START || status == ob::PlannerStatus::INVALID_GOAL))
        result.message += std::string(" (the proxy checker predicts the ") +
                          (status == ob::PlannerStatus::INVALID_START ? "start" : "goal") +
                          " in collision; the exact checker has it free)";
    }
    // OMPL 1.5's LazyPRM frees its roadmap's states in clear(), not in its destructor.
    planner->clear();
  }

  ob::PlannerPtr makeOmplPlanner(const ob::SpaceInformationPtr& si, std::uint64_t seed) const {
    auto ranged = [this](auto planner) {
      if (options_.range > 0) planner->setRange(options_.range);
      return planner;
    };
    const auto local_seed = static_cast<std::uint_fast32_t>((seed * 0xD1B54A32D192ED03ULL) >> 33) | 1u;
    if (name_ == "ompl-prm") {
      auto prm = std::make_shared<Seeded<og::PRM>>(si, local_seed);
      if (options_.k > 0) prm->setMaxNearestNeighbors(options_.k);
      return prm;
    }
    if (name_ == "ompl-lazyprm") return std::make_shared<og::LazyPRM>(si);
    if (name_ == "ompl-rrt") return ranged(std::make_shared<Seeded<og::RRT>>(si, local_seed));
    if (name_ == "ompl-sbl") return ranged(std::make_shared<Seeded<og::SBL>>(si, local_seed));
    if (name_ == "ompl-rrtstar") return ranged(std::make_shared<Seeded<og::RRTstar>>(si, local_seed));
    if (name_ == "ompl-informedrrtstar")
      return ranged(std::make_shared<Seeded<og::InformedRRTstar>>(si, local_seed));
    if (name_ == "ompl-fmt") return std::make_shared<og::FMT>(si);
    return ranged(std::make_shared<Seeded<og::RRTConnect>>(si, local_seed));
  }

  std::string name_;
  OmplOptions options_;
};

// OMPL's informational messages would drown the driver's log; set once, when the planners register.
bool quietOmpl() {
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  return true;
}
[[maybe_unused]] const bool kOmplQuiet = quietOmpl();

auto factory(const char* name) {
  return [name](const PlanningContext& context, const cspace::ParameterSet& params) {
    const OmplOptions o = OmplOptions::fromParameters(params);
    // OMPL's tree planners extend by `range` in loops that do not poll their termination: a range
    // far below the space's size never ends (RRTConnect with 1e-5 on Fig 3.5 ran past 120 s).
    const double diagonal = context.space.distance(context.space.lower(), context.space.upper());
    if (o.range > 0 && o.range < 1e-3 * diagonal) {
      std::ostringstream why;
      why << params.describe("range") << ": " << o.range << " is below 1e-3 of the space's diagonal (" << diagonal
          << "); 0 is OMPL's default";
      throw cspace::ScenarioError(why.str());
    }
    return std::make_unique<OmplPlanner>(name, context, o);
  };
}

}  // namespace

SVMP_REGISTER_PLANNER("ompl-prm", factory("ompl-prm"));
SVMP_REGISTER_PLANNER("ompl-lazyprm", factory("ompl-lazyprm"));
SVMP_REGISTER_PLANNER("ompl-rrtconnect", factory("ompl-rrtconnect"));
SVMP_REGISTER_PLANNER("ompl-rrt", factory("ompl-rrt"));
SVMP_REGISTER_PLANNER("ompl-sbl", factory("ompl-sbl"));
SVMP_REGISTER_PLANNER("ompl-rrtstar", factory("ompl-rrtstar"));
SVMP_REGISTER_PLANNER("ompl-fmt", factory("ompl-fmt"));
SVMP_REGISTER_PLANNER("ompl-informedrrtstar", factory("ompl-informedrrtstar"));

}  // namespace svmp::planners
