// Our planners as OMPL planners (planners/ompl/svm_planners.hpp): each solves through SimpleSetup on
// our checker with a path an independent checker re-checks densely; an expired termination condition
// stops them at once; the local planner's stalled descent is an approximate solution; getPlannerData
// is the roadmap and the path, its ends marked; the ParamSet lists the options' fields and setting one
// changes the options (bad values refused); a user's StateValidityChecker is used by the PRM (and one
// that throws is an error) and refused, with a reason, by SVMP.
#include <gtest/gtest.h>

#include <ompl/base/DiscreteMotionValidator.h>
#include <ompl/base/PlannerData.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/SimpleSetup.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <fstream>
#include <sstream>

#include "planners/ompl/scenario_setup.hpp"
#include "planners/ompl/svm_planners.hpp"
#include "planners/path_simplifier.hpp"
#include "planners/roadmap.hpp"
#include "test_world.hpp"

namespace svmp::ompl_planners {
namespace {

namespace og = ::ompl::geometric;

std::string scenarioText(const std::string& name) {
  std::ifstream in(std::string(SVMP_SOURCE_DIR) + "/bench/scenarios/" + name);
  EXPECT_TRUE(in.good()) << name;
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Our planner `name` on `scenario` through SimpleSetup, with the scenario's parameters.
struct OmplRun {
  OmplRun(const std::string& scenario, const std::string& name)
      : recheck(planners::test::makeWorld(scenarioText(scenario))),
        world(ScenarioWorld::make(recheck->scenario)),
        setup(world->simpleSetup()) {
    planner = makeSvmOmplPlanner(name, setup->getSpaceInformation(), recheck->scenario.paramsFor(name));
    setup->setPlanner(planner);
    setup->setup();
  }
  SvmOmplPlannerBase& ours() const { return *planner->as<SvmOmplPlannerBase>(); }
  std::vector<Eigen::VectorXd> path() const {
    std::vector<Eigen::VectorXd> q;
    for (const ob::State* s : setup->getSolutionPath().getStates())
      q.push_back(toConfiguration(s, world->context().space));
    return q;
  }
  std::unique_ptr<planners::test::World> recheck;  // the scenario and an independent FCL checker
  std::shared_ptr<const ScenarioWorld> world;
  std::shared_ptr<og::SimpleSetup> setup;
  ob::PlannerPtr planner;
};

struct Case {
  const char* planner;
  const char* scenario;
};
const Case kCases[] = {{"svmp", "thesis_fig2_6.yaml"}, {"prm", "thesis_fig2_6.yaml"},
                       {"local", "thesis_fig2_6.yaml"}, {"svpp", "svpp_2d_01.yaml"}};

TEST(OmplPlanners, EachSolvesThroughSimpleSetupWithACertifiedPath) {
  for (const Case& c : kCases) {
    OmplRun run(c.scenario, c.planner);
    run.ours().setSeed(1);
    const ob::PlannerStatus status = run.setup->solve(30.0);
    ASSERT_EQ(status, ob::PlannerStatus::EXACT_SOLUTION) << c.planner << ": " << run.ours().lastResult().message;
    EXPECT_TRUE(run.setup->haveExactSolutionPath()) << c.planner;
    EXPECT_FALSE(run.setup->getProblemDefinition()->hasApproximateSolution()) << c.planner;
    EXPECT_TRUE(run.ours().usesOwnChecker());
    EXPECT_TRUE(run.ours().lastResult().certified) << c.planner;
    EXPECT_GT(run.ours().lastResult().collision_checks, 0u) << c.planner;
    EXPECT_TRUE(planners::test::pathIsValid(*run.recheck, run.path())) << c.planner;
    // OMPL's own check of the path, on our checker and validator.
    EXPECT_TRUE(run.setup->getSolutionPath().check()) << c.planner;
    EXPECT_NEAR(run.setup->getSolutionPath().length(),
                planners::pathLength(run.path(), run.world->context().space), 1e-9) << c.planner;
  }
}

TEST(OmplPlanners, AnExpiredConditionStopsThemAtOnce) {
  for (const Case& c : kCases) {
    OmplRun run(c.scenario, c.planner);
    // Measured in work, not milliseconds (the machine is shared): at most one polling interval.
    const std::uint64_t before = run.world->context().checker.collisionChecks();
    const ob::PlannerStatus status = run.planner->solve(ob::PlannerTerminationCondition([] { return true; }));
    EXPECT_EQ(status, ob::PlannerStatus::TIMEOUT) << c.planner << ": " << status.asString();
    EXPECT_LE(run.world->context().checker.collisionChecks() - before, 1000u) << c.planner;
    EXPECT_FALSE(run.setup->haveSolutionPath()) << c.planner;
  }
}

TEST(OmplPlanners, PlannerDataIsTheRoadmapAndThePathWithItsEndsMarked) {
  for (const Case& c : kCases) {
    OmplRun run(c.scenario, c.planner);
    run.ours().setSeed(1);
    ASSERT_EQ(run.setup->solve(30.0), ob::PlannerStatus::EXACT_SOLUTION) << c.planner;
    ob::PlannerData data(run.setup->getSpaceInformation());
    run.planner->getPlannerData(data);
    const std::vector<Eigen::VectorXd>& path = run.ours().lastResult().path;
    const planners::Roadmap* roadmap = run.ours().planner()->view().roadmap;
    // The path's distinct waypoints that are not roadmap nodes are the vertices beyond the roadmap's.
    unsigned beyond = 0, checked = 0;
    for (size_t k = 0; k < path.size(); ++k) {
      bool known = std::find(path.begin(), path.begin() + k, path[k]) != path.begin() + k;
      for (int i = 0; roadmap && i < roadmap->numNodes() && !known; ++i) known = roadmap->node(i) == path[k];
      beyond += !known;
    }
    if (std::string(c.planner) == "svmp" || std::string(c.planner) == "prm") {
      ASSERT_NE(roadmap, nullptr) << c.planner;
      EXPECT_GT(roadmap->numNodes(), 10) << c.planner;
      EXPECT_LT(beyond, path.size()) << c.planner;  // the path runs through the roadmap
      // The checked edges, both ways (svmp's lazy edges that no query checked are candidates, not the
      // roadmap's).
      for (int i = 0; i < roadmap->numNodes(); ++i)
        for (const planners::Edge& e : roadmap->neighbours(i)) checked += e.checked;
      EXPECT_GT(checked, 0u) << c.planner;
    } else {
      EXPECT_EQ(roadmap, nullptr) << c.planner;
    }
    EXPECT_EQ(data.numVertices(), (roadmap ? roadmap->numNodes() : 0) + beyond) << c.planner;
    EXPECT_GE(data.numEdges(), checked) << c.planner;
    EXPECT_LE(data.numEdges(), checked + path.size() - 1) << c.planner;
    ASSERT_EQ(data.numStartVertices(), 1u) << c.planner;
    ASSERT_EQ(data.numGoalVertices(), 1u) << c.planner;
    const ob::SpaceInformationPtr& si = run.setup->getSpaceInformation();
    EXPECT_TRUE(si->equalStates(data.getStartVertex(0).getState(), run.setup->getSolutionPath().getState(0)));
    EXPECT_TRUE(si->equalStates(data.getGoalVertex(0).getState(),
                                run.setup->getSolutionPath().getStates().back())) << c.planner;
    // Start and goal are joined in the data along the path.
    std::vector<unsigned int> reached{data.getStartIndex(0)};
    std::vector<char> seen(data.numVertices(), 0);
    seen[reached[0]] = 1;
    for (size_t k = 0; k < reached.size(); ++k) {
      std::vector<unsigned int> next;
      data.getEdges(reached[k], next);
      for (unsigned int v : next)
        if (!seen[v]) seen[v] = 1, reached.push_back(v);
    }
    EXPECT_TRUE(seen[data.getGoalIndex(0)]) << c.planner;
  }
}

TEST(OmplPlanners, ParamSetListsTheOptionsAndSettingOneChangesThem) {
  OmplRun run("thesis_fig2_6.yaml", "svmp");
  auto& svmp = *run.planner->as<SvmpOmplPlanner>();
  std::map<std::string, std::string> listed;
  svmp.params().getParams(listed);
  for (const char* key : {"sigma", "C", "step", "samples_per_tree", "k", "repair_rounds", "kernel", "classes",
                          "truncated", "centre_in_passage"})
    EXPECT_TRUE(listed.count(key)) << key;
  EXPECT_EQ(listed.size(), svmp.parameters().declarations().size());
  EXPECT_EQ(svmp.params()["kernel"].getRangeSuggestion(), "fk,rbf");

  EXPECT_TRUE(svmp.params().setParam("sigma", "0.25"));
  EXPECT_EQ(svmp.options().sigma, 0.25);
  EXPECT_EQ(svmp.params()["sigma"].getValue(), "0.25");
  EXPECT_TRUE(svmp.params().setParam("samples_per_tree", "77"));
  EXPECT_EQ(svmp.options().samples_per_tree, 77);
  EXPECT_TRUE(svmp.params().setParam("truncated", "0"));
  EXPECT_FALSE(svmp.options().truncated);
  // Out of bounds or not in the allowed set: refused, the options unchanged.
  EXPECT_FALSE(svmp.params().setParam("sigma", "-1"));
  EXPECT_EQ(svmp.options().sigma, 0.25);
  EXPECT_FALSE(svmp.params().setParam("kernel", "polynomial"));
  EXPECT_EQ(svmp.options().kernel, "rbf");

  // The new options reach the planner: a PRM of 60 samples has at most 60 milestones.
  OmplRun prm("thesis_fig2_6.yaml", "prm");
  ASSERT_TRUE(prm.planner->params().setParam("samples", "60"));
  EXPECT_EQ(prm.planner->as<PrmOmplPlanner>()->options().samples, 60);
  prm.planner->solve(ob::timedPlannerTerminationCondition(10.0));
  EXPECT_LE(prm.ours().lastResult().milestones, 60u);
  EXPECT_GT(prm.ours().lastResult().milestones, 0u);
}

// A stalled descent (mu so small that a kink of |F| holds it) is OMPL's approximate solution.
TEST(OmplPlanners, TheLocalPlannersStalledDescentIsAnApproximateSolution) {
  OmplRun run("thesis_fig2_6.yaml", "local");
  ASSERT_TRUE(run.planner->params().setParam("mu", "0.001"));
  run.ours().setSeed(1);
  EXPECT_EQ(run.setup->solve(10.0), ob::PlannerStatus::APPROXIMATE_SOLUTION) << run.ours().lastResult().message;
  EXPECT_EQ(run.ours().lastResult().status, planners::PlanStatus::kLocalMinimum);
  EXPECT_FALSE(run.setup->haveExactSolutionPath());
  ASSERT_TRUE(run.setup->getProblemDefinition()->hasApproximateSolution());
  const std::vector<Eigen::VectorXd> path = run.path();
  ASSERT_GE(path.size(), 2u);
  EXPECT_LT((path.front() - run.recheck->query().start).norm(), 1e-9);
  const double to_goal = run.world->context().space.distance(path.back(), run.recheck->query().goal);
  EXPECT_GT(to_goal, 0.01);
  EXPECT_NEAR(run.setup->getProblemDefinition()->getSolutionDifference(), to_goal, 1e-9);
}

TEST(OmplPlanners, ABadParameterInTheConstructorThrows) {
  auto world = ScenarioWorld::make(planners::test::makeWorld(scenarioText("thesis_fig2_6.yaml"))->scenario);
  EXPECT_THROW(SvmpOmplPlanner(world->spaceInformation(), cspace::ParameterSet("t", "", {{"sigma", "0"}})),
               cspace::ScenarioError);
  EXPECT_THROW(PrmOmplPlanner(world->spaceInformation(), cspace::ParameterSet("t", "", {{"sample", "9"}})),
               cspace::ScenarioError);
}

// Our checker with OMPL's own motion validator: the planner validates segments through it and still
// certifies the path with our certifier.
TEST(OmplPlanners, OurCheckerWithOmplsMotionValidatorStillCertifies) {
  OmplRun run("thesis_fig2_6.yaml", "prm");
  const ob::SpaceInformationPtr& si = run.setup->getSpaceInformation();
  si->setMotionValidator(std::make_shared<ob::DiscreteMotionValidator>(si));
  run.planner->setup();
  run.ours().setSeed(1);
  ASSERT_EQ(run.planner->solve(ob::timedPlannerTerminationCondition(10.0)), ob::PlannerStatus::EXACT_SOLUTION)
      << run.ours().lastResult().message;
  EXPECT_TRUE(run.ours().usesOwnChecker());
  EXPECT_TRUE(run.ours().lastResult().certified);
  EXPECT_GT(run.ours().lastResult().local_planner_calls, 0u);
  EXPECT_GT(si->getMotionValidator()->getValidMotionCount(), 0u);  // OMPL's validator did the work
  EXPECT_TRUE(planners::test::pathIsValid(*run.recheck, run.path()));
}

// Benchmark reads the SpaceInformation's parameters, the default projection's cell sizes among them:
// they must be the projection's that is in use (OMPL 1.5's identity projection is replaced in 2-D).
TEST(OmplPlanners, TheSpaceInformationsParametersAreItsProjections) {
  auto world = ScenarioWorld::make(planners::test::makeWorld(scenarioText("thesis_fig2_6.yaml"))->scenario);
  const ob::SpaceInformationPtr si = world->spaceInformation();
  const auto& projection = si->getStateSpace()->getDefaultProjection();
  ASSERT_EQ(projection->getDimension(), 2u);
  ASSERT_EQ(projection->getCellSizes().size(), 2u);  // set up (a projection registered after setup is not)
  std::map<std::string, std::string> params;
  si->params().getParams(params);
  ASSERT_EQ(params.count("projection.cellsize.0"), 1u) << params.size();
  EXPECT_NEAR(std::stod(params["projection.cellsize.0"]), projection->getCellSizes()[0], 1e-5);  // 6 digits
  const auto& bounds = si->getStateSpace()->as<ob::RealVectorStateSpace>()->getBounds();
  EXPECT_DOUBLE_EQ(projection->getCellSizes()[1], (bounds.high[1] - bounds.low[1]) / 20.0);
}

// A user's checker: the unit square without a disc of radius 0.25 at its centre, counting its calls.
class DiscChecker final : public ob::StateValidityChecker {
 public:
  using ob::StateValidityChecker::StateValidityChecker;
  bool isValid(const ob::State* s) const override {
    ++calls;
    const auto* v = s->as<ob::RealVectorStateSpace::StateType>();
    return std::hypot(v->values[0] - 0.5, v->values[1] - 0.5) > 0.25;
  }
  mutable std::atomic<long> calls{0};
};

std::shared_ptr<og::SimpleSetup> discSetup(std::shared_ptr<DiscChecker>& checker) {
  auto space = std::make_shared<ob::RealVectorStateSpace>(2);
  space->setBounds(0.0, 1.0);
  auto setup = std::make_shared<og::SimpleSetup>(space);
  checker = std::make_shared<DiscChecker>(setup->getSpaceInformation());
  setup->setStateValidityChecker(checker);
  setup->getSpaceInformation()->setStateValidityCheckingResolution(0.002);
  ob::ScopedState<> start(space), goal(space);
  start[0] = start[1] = 0.2;
  goal[0] = goal[1] = 0.8;
  setup->setStartAndGoalStates(start, goal);
  return setup;
}

TEST(OmplPlanners, AUsersCheckerIsUsedByThePrm) {
  std::shared_ptr<DiscChecker> checker;
  auto setup = discSetup(checker);
  auto prm = std::make_shared<PrmOmplPlanner>(setup->getSpaceInformation());
  prm->setSeed(3);
  setup->setPlanner(prm);
  ASSERT_EQ(setup->solve(10.0), ob::PlannerStatus::EXACT_SOLUTION) << prm->lastResult().message;
  EXPECT_FALSE(prm->usesOwnChecker());
  // Every configuration our PRM tested went to the user's checker (its motion validator asks more).
  EXPECT_GT(prm->lastResult().collision_checks, 500u);
  EXPECT_GE(checker->calls.load(), static_cast<long>(prm->lastResult().collision_checks));
  EXPECT_FALSE(prm->lastResult().certified);  // no certifier: the SpaceInformation's guarantee only
  og::PathGeometric path = setup->getSolutionPath();
  path.interpolate(2000);
  for (const ob::State* s : path.getStates()) {
    const auto* v = s->as<ob::RealVectorStateSpace::StateType>();
    EXPECT_GT(std::hypot(v->values[0] - 0.5, v->values[1] - 0.5), 0.25);
  }
}

// A review's finding: the PRM tests its samples in an OpenMP loop, and an exception leaving one ends
// the program. A user's checker that throws now reaches solve()'s error report instead.
class ThrowingChecker final : public ob::StateValidityChecker {
 public:
  using ob::StateValidityChecker::StateValidityChecker;
  bool isValid(const ob::State* s) const override {
    if (s->as<ob::RealVectorStateSpace::StateType>()->values[0] > 0.9) throw std::runtime_error("no map there");
    return true;
  }
};

TEST(OmplPlanners, AUsersCheckerThatThrowsIsAnErrorNotAnEnd) {
  std::shared_ptr<DiscChecker> unused;
  auto setup = discSetup(unused);
  setup->setStateValidityChecker(std::make_shared<ThrowingChecker>(setup->getSpaceInformation()));
  auto prm = std::make_shared<PrmOmplPlanner>(setup->getSpaceInformation());
  prm->setSeed(3);
  setup->setPlanner(prm);
  EXPECT_EQ(setup->solve(10.0), ob::PlannerStatus::ABORT);
  EXPECT_EQ(prm->lastResult().status, planners::PlanStatus::kInvalidInput);
  EXPECT_EQ(prm->lastResult().message, "no map there");
}

// A probe's finding: states were kept within the bounds on the way in, so a start at (-3, 0.5) gave an
// "exact" path from (0, 0.5). OMPL's own planners skip such a start; ours now refuse it, and a goal so.
TEST(OmplPlanners, AStartOrGoalBeyondTheBoundsIsInvalid) {
  for (const bool start_out : {true, false}) {
    std::shared_ptr<DiscChecker> checker;
    auto setup = discSetup(checker);
    const auto space = setup->getStateSpace();
    ob::ScopedState<> start(space), goal(space);
    start[0] = start_out ? -3.0 : 0.2, start[1] = 0.2;
    goal[0] = 0.8, goal[1] = start_out ? 0.8 : 1.5;
    setup->setStartAndGoalStates(start, goal);
    auto prm = std::make_shared<PrmOmplPlanner>(setup->getSpaceInformation());
    setup->setPlanner(prm);
    EXPECT_EQ(setup->solve(1.0), start_out ? ob::PlannerStatus::INVALID_START : ob::PlannerStatus::INVALID_GOAL);
    EXPECT_FALSE(setup->haveExactSolutionPath());
    EXPECT_NE(prm->lastResult().message.find(start_out ? "start state is outside" : "goal state is outside"),
              std::string::npos) << prm->lastResult().message;
  }
}

TEST(OmplPlanners, SvmpRefusesAUsersCheckerAndSaysWhy) {
  std::shared_ptr<DiscChecker> checker;
  auto setup = discSetup(checker);
  auto svmp = std::make_shared<SvmpOmplPlanner>(setup->getSpaceInformation());
  setup->setPlanner(svmp);
  EXPECT_EQ(setup->solve(1.0), ob::PlannerStatus::ABORT);
  EXPECT_NE(svmp->lastResult().message.find("which obstacle a configuration hits"), std::string::npos)
      << svmp->lastResult().message;
  EXPECT_EQ(checker->calls.load(), 0);
}

}  // namespace
}  // namespace svmp::ompl_planners
