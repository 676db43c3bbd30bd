#pragma once
// Our planners as OMPL planners (OMPL 1.5 API: ompl::base::Planner, ParamSet, PlannerData,
// PlannerTerminationCondition; Sucan, Moll, Kavraki, IEEE RAM 2012), so they run wherever planning
// researchers already work: SimpleSetup, ompl::tools::Benchmark, Planner Arena. SvmpOmplPlanner (thesis
// ch. 3-4), PrmOmplPlanner (the thesis' classical PRM), LocalOmplPlanner (thesis ch. 2) and
// SvppOmplPlanner (Miura 2006) wrap SvmpPlanner, PrmPlanner, LocalPlanner and SvppPlanner.
//
//   auto world = svmp::ompl_planners::ScenarioWorld::make(svmp::cspace::loadScenario(file));
//   auto setup = world->simpleSetup();                        // our FCL checker inside OMPL
//   setup->setPlanner(std::make_shared<svmp::ompl_planners::SvmpOmplPlanner>(setup->getSpaceInformation()));
//   setup->getPlanner()->params().setParam("sigma", "0.2");
//   if (setup->solve(5.0) == ompl::base::PlannerStatus::EXACT_SOLUTION) setup->getSolutionPath().printAsMatrix(std::cout);
//
// - Problem: the ProblemDefinition's first start state and a GoalState (other goals give
//   UNRECOGNIZED_GOAL_TYPE).
// - Termination: solve(ptc) plans under a planners::Termination that fires when ptc does; every planner
//   polls it between steps and in its long loops.
// - Parameters: each Options' fields, declared in params() with their type, default and range as the
//   Options' fromParameters reads them (cspace::ParameterSet::declarations); ParamSet::setParam checks
//   the value as a scenario file's would and returns false (OMPL logs why) when it is out of bounds.
//   A change takes effect at the next solve (the roadmap is kept only while the options are).
// - The checker: with our own (ContextValidityChecker, e.g. from ScenarioWorld) the planner uses the
//   whole PlanningContext: obstacle ids for SVMP's classes, the robot, the certifier and the repairer,
//   so a solved path is certified exactly as svmp-plan certifies it (every segment proven free by FCL
//   distances and the displacement bound). With any other StateValidityChecker (a user's) the PRM runs
//   on it and its MotionValidator (planners/ompl/foreign_checker.hpp, one thread): the guarantee is
//   then the SpaceInformation's own, every segment passed its MotionValidator. SVMP, the local planner
//   and SVPP need what only our checker knows (which obstacle a configuration hits, the robot's
//   links, the obstacles' polygons): with a foreign checker solve() logs why (OMPL_ERROR) and returns
//   ABORT.
// - Results: a solved path is added to the ProblemDefinition as a PathGeometric, EXACT_SOLUTION; the
//   local planner's descent that stalls (kLocalMinimum) gives its partial path as an APPROXIMATE_SOLUTION
//   (difference = distance to the goal; checked by the motion validator, not certified); a timeout
//   gives TIMEOUT, a start or goal in collision INVALID_START / INVALID_GOAL, other failures ABORT.
//   The roadmap (SVMP, PRM) is kept across solve() calls until clear(), as OMPL's PRM keeps its own.
//   lastResult() has the counters of the last solve (collision checks, local planner calls, ...).
// - getPlannerData: the roadmap's milestones and edges (SVMP, PRM); the last path for the others.
// - Seeds: each solve draws its seed from an ompl::RNG (OMPL's global seed makes runs repeatable),
//   unless setSeed() fixed one.
//
// Thread safety: as any OMPL planner, one solve at a time.
#include <ompl/base/Planner.h>
#include <ompl/util/RandomNumbers.h>

#include <memory>
#include <optional>
#include <string>

#include "cspace/scenario/parameters.hpp"
#include "planners/local_planner.hpp"
#include "planners/planner.hpp"
#include "planners/prm_planner.hpp"
#include "planners/svmp_planner.hpp"
#include "planners/svpp_planner.hpp"

namespace svmp::ompl_planners {

namespace ob = ::ompl::base;

// What the four share; the typed subclasses below hold the options. The planner itself is made by the
// registry (planners/planner_registry.hpp) from the same parameters, so its checks are svmp-plan's.
class SvmOmplPlannerBase : public ob::Planner {
 public:
  ~SvmOmplPlannerBase() override;
  ob::PlannerStatus solve(const ob::PlannerTerminationCondition& ptc) override;
  void clear() override;
  void setup() override;
  void getPlannerData(ob::PlannerData& data) const override;

  // The counters, status and message of the last solve().
  const planners::PlanResult& lastResult() const { return last_; }
  // The parameters set so far (scenario keys), e.g. from a scenario's `planners.svmp` section.
  const cspace::ParameterSet& parameters() const { return params_; }
  // Fixes the seed of the next solve() calls (each adds one); unset, seeds come from ompl::RNG.
  void setSeed(std::uint64_t seed) { seed_ = seed; }
  // The planner inside (null before setup() or after a parameter changed), for inspection.
  const planners::Planner* planner() const { return planner_.get(); }
  // False when the SpaceInformation's checker is not ours (see above).
  bool usesOwnChecker() const { return own_checker_; }

 protected:
  // `needs_own_checker`: why the planner cannot run on a foreign checker; empty when it can.
  SvmOmplPlannerBase(const ob::SpaceInformationPtr& si, const std::string& name, cspace::ParameterSet params,
                     std::string needs_own_checker);
  // Reads and validates the options from `params` (throws cspace::ScenarioError or
  // std::invalid_argument); keeps them only when they are good.
  virtual void readOptions(const cspace::ParameterSet& params) = 0;
  // Called by the subclass constructors once the options exist: reads `params` (a key no option reads
  // throws cspace::ScenarioError), declares every key.
  void declareParameters();

 private:
  struct ForeignSeams;
  void setParameter(const std::string& key, const std::string& value);
  std::string currentValue(const std::string& key) const;
  // Builds the context and the planner for the current SpaceInformation; "" or why not.
  std::string prepare();

  cspace::ParameterSet params_;
  std::string needs_own_checker_;
  bool own_checker_ = false;
  std::string unusable_;  // why this SpaceInformation cannot be planned on ("" when it can)
  std::unique_ptr<ForeignSeams> foreign_;
  std::optional<planners::PlanningContext> context_;
  std::unique_ptr<planners::Planner> planner_;
  planners::PlanResult last_;
  std::optional<std::uint64_t> seed_;
  ::ompl::RNG rng_;
};

template <class OptionsT>
class SvmOmplPlanner : public SvmOmplPlannerBase {
 public:
  const OptionsT& options() const { return options_; }

 protected:
  SvmOmplPlanner(const ob::SpaceInformationPtr& si, const std::string& name, cspace::ParameterSet params,
                 std::string needs_own_checker)
      : SvmOmplPlannerBase(si, name, std::move(params), std::move(needs_own_checker)) {
    declareParameters();
  }
  void readOptions(const cspace::ParameterSet& params) override {
    OptionsT options = OptionsT::fromParameters(params);
    if (const std::string why = options.validate(); !why.empty()) throw std::invalid_argument(why);
    options_ = options;
  }

 private:
  OptionsT options_;
};

// Throw cspace::ScenarioError when `params` (scenario keys of that planner) are bad.
class SvmpOmplPlanner final : public SvmOmplPlanner<planners::SvmpOptions> {
 public:
  explicit SvmpOmplPlanner(const ob::SpaceInformationPtr& si, cspace::ParameterSet params = {})
      : SvmOmplPlanner(si, "svmp", std::move(params),
                       "SVMP grows a tree inside each obstacle and learns one class per obstacle: it needs to "
                       "know which obstacle a configuration hits") {}
};

class PrmOmplPlanner final : public SvmOmplPlanner<planners::PrmOptions> {
 public:
  explicit PrmOmplPlanner(const ob::SpaceInformationPtr& si, cspace::ParameterSet params = {})
      : SvmOmplPlanner(si, "prm", std::move(params), "") {}
};

class LocalOmplPlanner final : public SvmOmplPlanner<planners::LocalPlannerOptions> {
 public:
  explicit LocalOmplPlanner(const ob::SpaceInformationPtr& si, cspace::ParameterSet params = {})
      : SvmOmplPlanner(si, "local", std::move(params),
                       "the local planner samples the obstacles' surfaces by the robot's inverse kinematics") {}
};

class SvppOmplPlanner final : public SvmOmplPlanner<planners::SvppOptions> {
 public:
  explicit SvppOmplPlanner(const ob::SpaceInformationPtr& si, cspace::ParameterSet params = {})
      : SvmOmplPlanner(si, "svpp", std::move(params),
                       "SVPP separates the obstacles' shapes around a point robot") {}
};

// One of the four by its registry name (svmp, prm, local, svpp); null for another name.
ob::PlannerPtr makeSvmOmplPlanner(const std::string& name, const ob::SpaceInformationPtr& si,
                                  cspace::ParameterSet params = {});

}  // namespace svmp::ompl_planners
