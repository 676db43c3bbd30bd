// The seams of docs/architecture.md: a planner registered from this file alone runs in the driver, a
// validity checker swapped into PlanningContext is the only one every planner (and the OMPL bridge)
// calls, a time limit ends every planner with kTimeout, a built roadmap answers several queries, and
// the registry's defaults are the option structs' defaults.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <fstream>
#include <iterator>
#include <sstream>

#include "bench/experiments/experiment.hpp"
#include "planners/local_planner.hpp"
#include "planners/planner_registry.hpp"
#include "planners/prm_planner.hpp"
#include "planners/svmp_planner.hpp"
#include "test_world.hpp"

namespace svmp::planners {
namespace {

using test::gapScenario;
using test::makeWorld;

// The simplest planner there is: the straight line, when the validator accepts it.
class StraightLinePlanner final : public Planner {
 public:
  using Planner::Planner;
  std::string name() const override { return "test-straight"; }
  void clear() override { forgetBuild(); }

 protected:
  void buildRoadmap(std::uint64_t, const Termination&, PlanResult& result) override {
    result.status = PlanStatus::kSolved;
  }
  void answer(const cspace::Query& q, std::uint64_t, const Termination&, PlanResult& result) override {
    if (!context_.validator.isValid(q.start, q.goal)) {
      result.message = "the straight line is blocked";
      return;
    }
    result.status = PlanStatus::kSolved;
    result.path = {q.start, q.goal};
  }
};

SVMP_REGISTER_PLANNER("test-straight", [](const PlanningContext& c, const cspace::ParameterSet&) {
  return std::make_unique<StraightLinePlanner>(c);
});

TEST(Seams, PlannerRegisteredFromATestFileRunsInTheDriver) {
  const std::string path = std::string(SVMP_SOURCE_DIR) + "/bench/scenarios/thesis_fig3_5.yaml";
  const cspace::Scenario scenario = cspace::loadScenario(path);
  experiments::DriverOptions options;
  options.scenario = path;
  options.planners = {"test-straight", "prm"};
  options.runs = 2;
  std::ostringstream log, table;
  const auto results = experiments::runExperiment(scenario, options, log);
  ASSERT_EQ(results.size(), 2u);
  EXPECT_EQ(results[0].planner, "test-straight");
  ASSERT_EQ(results[0].runs.size(), 2u);
  // Fig 3.5's start and goal are separated by obstacles: the straight line fails, and says why.
  EXPECT_EQ(results[0].runs[0].result.status, PlanStatus::kFailed);
  EXPECT_EQ(results[0].runs[0].result.message, "the straight line is blocked");
  EXPECT_EQ(results[0].runs[0].result.local_planner_calls, 1u);
  experiments::printTable(scenario, options, results, table);
  EXPECT_NE(table.str().find("test-straight"), std::string::npos);
}

// Forwards to the FCL checker and counts what it was asked.
class CountingChecker final : public cspace::ValidityChecker {
 public:
  explicit CountingChecker(const cspace::ValidityChecker& inner) : inner_(inner) {}
  const robots::Robot& robot() const override { return inner_.robot(); }
  const cspace::Environment& environment() const override { return inner_.environment(); }
  int check(const Eigen::Ref<const Eigen::VectorXd>& q) const override {
    ++asked_;
    return inner_.check(q);
  }
  int checkIncludingVirtual(const Eigen::Ref<const Eigen::VectorXd>& q) const override {
    ++asked_;
    return inner_.checkIncludingVirtual(q);
  }
  bool hits(const Eigen::Ref<const Eigen::VectorXd>& q, int id) const override {
    ++asked_;
    return inner_.hits(q, id);
  }
  double clearance(const Eigen::Ref<const Eigen::VectorXd>& q) const override { return inner_.clearance(q); }
  bool checksSelfCollision() const override { return inner_.checksSelfCollision(); }
  std::uint64_t collisionChecks() const override { return asked_; }
  std::uint64_t asked() const { return asked_; }

 private:
  const cspace::ValidityChecker& inner_;
  mutable std::atomic<std::uint64_t> asked_{0};
};

TEST(Seams, SwappedValidityCheckerIsTheOneEveryPlannerCalls) {
  auto w = makeWorld(gapScenario(0.03,
                                 "  svmp: {sigma: 0.06, step: 0.05, samples_per_tree: 100}\n"
                                 "  prm: {samples: 300}\n"
                                 "  ompl-rrtconnect: {time_limit: 2}\n"
                                 "  ompl-prm: {time_limit: 0.05}\n"
                                 "  ompl-lazyprm: {time_limit: 0.05}\n"));
  const CountingChecker counting(w->checker);
  const cspace::DiscreteMotionValidator validator(counting, w->space, w->scenario.resolution);
  const PlanningContext context{w->space, counting, validator, 1};
  for (const std::string name : {"svmp", "prm", "ompl-rrtconnect", "ompl-prm", "ompl-lazyprm"}) {
    if (name.rfind("ompl-", 0) == 0 && plannerNames().end() == std::find(plannerNames().begin(), plannerNames().end(), name))
      continue;  // built without OMPL
    auto planner = makePlanner(name, context, w->scenario.paramsFor(name));
    const std::uint64_t fcl_before = w->checker.collisionChecks(), asked_before = counting.asked();
    const PlanResult r = planner->solve(w->query(), 1);
    const std::uint64_t fcl = w->checker.collisionChecks() - fcl_before, asked = counting.asked() - asked_before;
    EXPECT_GT(asked, 0u) << name;
    // Nothing reached FCL except through the swapped checker, and the result counts what it was asked.
    EXPECT_EQ(fcl, asked) << name;
    EXPECT_EQ(r.collision_checks, asked) << name;
  }
}

// A stop is honoured within a bounded amount of work, measured in collision checks rather than
// milliseconds (a shared machine makes wall-clock bounds flaky): the condition fires once the checker
// has counted 1,000 checks, and the planner must return soon after (without it these runs take
// millions of checks).
TEST(Seams, AStopEndsEveryPlannerWithTimeoutWithinBoundedWork) {
  auto w = makeWorld(gapScenario(0.01,
                                 "  svmp: {sigma: 0.03, step: 0.01, samples_per_tree: 20000}\n"
                                 "  prm: {samples: 2000000}\n"
                                 "  ompl-prm: {time_limit: 60}\n"));
  for (const std::string name : {"svmp", "prm", "ompl-prm"}) {
    if (name == "ompl-prm" && plannerNames().end() == std::find(plannerNames().begin(), plannerNames().end(), name))
      continue;
    auto planner = w->planner(name);
    const std::uint64_t before = w->checker.collisionChecks();
    const PlanResult r = planner->solve(
        w->query(), 1, Termination::when([&] { return w->checker.collisionChecks() - before >= 1000; }));
    EXPECT_EQ(r.status, PlanStatus::kTimeout) << name << ": " << planStatusName(r.status) << " " << r.message;
    EXPECT_GE(r.collision_checks, 1000u) << name;
    EXPECT_LT(r.collision_checks, 6000u) << name;
    std::printf("[ info     ] %s stopped after %llu checks\n", name.c_str(),
                static_cast<unsigned long long>(r.collision_checks));
  }
}

TEST(Seams, LocalPlannerHonoursTheTimeLimit) {
  std::ifstream file(std::string(SVMP_SOURCE_DIR) + "/bench/scenarios/thesis_fig2_6.yaml");
  const std::string yaml((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  auto w = makeWorld(yaml);
  auto local = w->planner("local");
  ASSERT_TRUE(local->solve(w->query(), 1).solved());
  // Nothing to build ahead, and each query starts from its own samples.
  ASSERT_TRUE(local->build(1).solved());
  EXPECT_TRUE(local->query(w->query(), 1).solved());
  EXPECT_TRUE(local->query(w->query(), 1).solved());
  local->clear();
  EXPECT_THROW(local->query(w->query(), 1), std::logic_error);
  const PlanResult r = w->planner("local")->solve(w->query(), 1, Termination::when([] { return true; }));
  EXPECT_EQ(r.status, PlanStatus::kTimeout) << planStatusName(r.status) << " " << r.message;
}

TEST(Seams, BuiltRoadmapAnswersManyQueries) {
  auto w = makeWorld(gapScenario(0.03, "  svmp: {sigma: 0.06, step: 0.05, samples_per_tree: 200}\n  prm: {samples: 2000}\n"));
  for (const std::string name : {"svmp", "prm"}) {
    auto planner = w->planner(name);
    EXPECT_THROW(planner->query(w->query(), 1), std::logic_error) << name;
    const PlanResult built = planner->build(7);
    ASSERT_TRUE(built.solved()) << name << ": " << built.message;
    EXPECT_GT(built.milestones, 0u);
    const cspace::Query reverse{w->query().goal, w->query().start, {}};
    const cspace::Query other{Eigen::Vector2d(0.1, 0.9), Eigen::Vector2d(0.9, 0.1), {}};
    for (const auto& q : {w->query(), reverse, other}) {
      const PlanResult r = planner->query(q, 7);
      ASSERT_TRUE(r.solved()) << name << ": " << r.message;
      EXPECT_EQ((r.path.front() - q.start).norm(), 0.0);
      EXPECT_EQ((r.path.back() - q.goal).norm(), 0.0);
      // Sampled at the resolution (no certifier here): free up to what checks that far apart can miss.
      for (size_t i = 0; i + 1 < r.path.size(); ++i)
        EXPECT_TRUE(test::segmentIsValid(*w, r.path[i], r.path[i + 1], w->scenario.resolution)) << name;
      // A query costs a small part of the build: it connects two configurations.
      EXPECT_LT(r.collision_checks, built.collision_checks) << name;
    }
    // solve() from the same seed builds the same roadmap and finds the same path as build() + query().
    const PlanResult again = planner->query(w->query(), 7);
    const PlanResult solved = planner->solve(w->query(), 7);
    ASSERT_EQ(again.path.size(), solved.path.size()) << name;
    for (size_t i = 0; i < again.path.size(); ++i) EXPECT_EQ(again.path[i], solved.path[i]) << name;
  }
}

TEST(Seams, RegistryDefaultsAreTheOptionStructsDefaults) {
  const cspace::ParameterSet empty("test.yaml", "planners.x.", {});
  EXPECT_TRUE(SvmpOptions::fromParameters(empty) == SvmpOptions{});
  EXPECT_TRUE(PrmOptions::fromParameters(empty) == PrmOptions{});
  EXPECT_TRUE(LocalPlannerOptions::fromParameters(empty) == LocalPlannerOptions{});
  // The descent step follows sigma unless given.
  SvmpOptions o;
  o.sigma = 0.37;
  EXPECT_EQ(o.descent().max_step, 0.37);
  o.descent_step = 0.01;
  EXPECT_EQ(o.descent().max_step, 0.01);
  // The thin-tree limit is a switch like the other departures from the thesis: 0 turns it off.
  EXPECT_EQ(SvmpOptions::fromParameters(cspace::ParameterSet("t.yaml", "planners.svmp.", {{"tree_expansions_per_node", "0"}}))
                .tree_expansions_per_node,
            0);
  EXPECT_THROW(SvmpOptions::fromParameters(
                   cspace::ParameterSet("t.yaml", "planners.svmp.", {{"tree_expansions_per_node", "-1"}})),
               cspace::ScenarioError);
}

// A tiny fk_sigma gives the kernel an infinite gamma: refused when read, naming the field and value.
TEST(Seams, ATinyFkSigmaIsRefusedWithItsField) {
  try {
    SvmpOptions::fromParameters(cspace::ParameterSet("t.yaml", "planners.svmp.", {{"fk_sigma", "1e-300"}}));
    FAIL() << "fk_sigma 1e-300 accepted";
  } catch (const cspace::ScenarioError& e) {
    EXPECT_NE(std::string(e.what()).find("planners.svmp.fk_sigma"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("1e-300"), std::string::npos) << e.what();
  }
  for (const char* fine : {"-1", "0", "1e-09", "0.2"})
    EXPECT_NO_THROW(SvmpOptions::fromParameters(cspace::ParameterSet("t.yaml", "planners.svmp.", {{"fk_sigma", fine}})))
        << fine;
}

}  // namespace
}  // namespace svmp::planners
