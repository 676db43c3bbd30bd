// The planners end to end: valid paths, invalid queries, determinism, the factory's errors, and the
// narrow passage that SVMP's boundary milestones are made for (its repair: repair_test.cpp; fewer
// than two obstacle classes: few_obstacles_test.cpp).
#include <gtest/gtest.h>

#include "planners/path_simplifier.hpp"
#include "planners/prm_planner.hpp"
#include "planners/roadmap_builder.hpp"
#include "planners/svmp_planner.hpp"
#include "test_world.hpp"

namespace svmp::planners {
namespace {

using test::gapScenario;
using test::makeWorld;
using test::pathIsValid;

// Usable gap 0.03, resolution 0.002 (gapScenario).
const std::string kPlanners =
    "  svmp: {sigma: 0.06, C: 100, step: 0.05, samples_per_tree: 200, k: 10}\n"
    "  prm: {samples: 2000, k: 10}\n"
    "  ompl-rrtconnect: {time_limit: 5}\n"
    "  ompl-prm: {time_limit: 0.2}\n";

void expectSolvedWithValidPath(const std::string& planner, std::uint64_t seed) {
  auto w = makeWorld(gapScenario(0.03, kPlanners));
  auto p = w->planner(planner);
  const PlanResult r = p->solve(w->query(), seed);
  ASSERT_EQ(r.status, PlanStatus::kSolved) << planner << ": " << planStatusName(r.status) << " " << r.message;
  EXPECT_TRUE(pathIsValid(*w, r.path)) << planner;
  EXPECT_GT(r.collision_checks, 0u);
  EXPECT_GT(r.local_planner_calls, 0u);
  // The path crosses the wall, so it passes through the gap: some configuration has x in the wall's
  // span and y within the gap.
  bool through_gap = false;
  for (size_t i = 0; i + 1 < r.path.size() && !through_gap; ++i)
    for (int s = 0; s <= 100 && !through_gap; ++s) {
      const Eigen::VectorXd q = r.path[i] + (s / 100.0) * (r.path[i + 1] - r.path[i]);
      through_gap = std::abs(q.x() - 0.5) < 0.09 && std::abs(q.y() - 0.5) <= 0.016;
    }
  EXPECT_TRUE(through_gap) << planner;
}

TEST(Planners, SvmpPathIsValid) {
  for (std::uint64_t seed : {1, 2}) expectSolvedWithValidPath("svmp", seed);
}
TEST(Planners, PrmPathIsValid) { expectSolvedWithValidPath("prm", 1); }
#ifdef SVMP_WITH_OMPL
TEST(Planners, OmplRrtConnectPathIsValid) { expectSolvedWithValidPath("ompl-rrtconnect", 1); }
// A rival's tree is copied out of OMPL only to count it for the table: that time is kept apart, and
// the driver does not charge it to the rival (a 2 s PRM timeout used to report 3.4 s).
TEST(Planners, CountingARivalsRoadmapIsKeptApartFromItsTime) {
  auto w = makeWorld(gapScenario(0.03, kPlanners));
  const PlanResult rival = w->planner("ompl-rrtconnect")->solve(w->query(), 1);
  ASSERT_TRUE(rival.solved()) << rival.message;
  EXPECT_GT(rival.milestones, 0u);
  EXPECT_GT(rival.counting_ms, 0.0);
  EXPECT_EQ(w->planner("svmp")->solve(w->query(), 1).counting_ms, 0.0);  // it keeps its own counts
}
#endif

TEST(Planners, SvmpCountersDescribeTheRoadmap) {
  auto w = makeWorld(gapScenario(0.03, kPlanners));
  SvmpOptions o;
  o.sigma = 0.06;
  o.step = 0.05;
  o.samples_per_tree = 200;
  SvmpPlanner svmp(w->context, o);
  const PlanResult r = svmp.solve(w->query(), 3);
  ASSERT_TRUE(r.solved()) << r.message;
  EXPECT_EQ(r.milestones, static_cast<std::uint64_t>(svmp.roadmap().numNodes()));
  EXPECT_EQ(r.roadmap_edges, static_cast<std::uint64_t>(svmp.roadmap().numEdges()));
  EXPECT_EQ(r.support_vectors, static_cast<std::uint64_t>(svmp.supportVectors()));
  EXPECT_GT(r.support_vectors, 0u);
  // Milestones are collision-free.
  for (const auto& q : svmp.roadmap().nodes()) {
    EXPECT_TRUE(w->checker.isValid(q)) << q.transpose();
  }
  // Every checked roadmap edge is a valid straight line up to what checks a resolution apart can miss
  // (re-checked by an independent checker, finer); lazy edges the query did not use may be unchecked.
  int checked = 0;
  for (int i = 0; i < svmp.roadmap().numNodes(); ++i)
    for (const Edge& e : svmp.roadmap().neighbours(i)) {
      const Eigen::VectorXd& a = svmp.roadmap().node(i);
      const Eigen::VectorXd& b = svmp.roadmap().node(e.to);
      EXPECT_NEAR(e.cost, w->space.distance(a, b), 1e-12);
      if (!e.checked) continue;
      ++checked;
      ASSERT_TRUE(test::segmentIsValid(*w, a, b, w->scenario.resolution)) << "edge " << i << "-" << e.to;
    }
  EXPECT_GT(checked, 0);
  ASSERT_GE(r.path.size(), 2u);
  EXPECT_TRUE(r.path.front() == w->query().start);
  EXPECT_TRUE(r.path.back() == w->query().goal);
  EXPECT_TRUE(pathIsValid(*w, r.path));
}

// SVMP's milestones in a narrow passage are centred in it (centreAlongNormal), not merely free: in a
// 0.002-wide gap every milestone within the wall lies within a quarter of the gap of its middle.
TEST(Planners, SvmpMilestonesInAPassageAreCentredInIt) {
  const double gap = 0.002;
  auto w = makeWorld(gapScenario(gap, "  svmp: {defer_centring: false}\n"));
  SvmpPlanner svmp(w->context, SvmpOptions::fromParameters(w->scenario.paramsFor("svmp")));
  ASSERT_TRUE(svmp.build(1).solved());
  int inside = 0;
  for (const auto& q : svmp.roadmap().nodes())
    if (std::abs(q.x() - 0.5) < 0.1) {
      ++inside;
      EXPECT_NEAR(q.y(), 0.5, 0.25 * gap) << q.transpose();
    }
  EXPECT_GT(inside, 0) << "no milestone in the passage";
}

void expectSameResult(const PlanResult& a, const PlanResult& b) {
  EXPECT_EQ(a.status, b.status);
  ASSERT_EQ(a.path.size(), b.path.size());
  for (size_t i = 0; i < a.path.size(); ++i) EXPECT_TRUE(a.path[i] == b.path[i]) << "path point " << i;
  EXPECT_EQ(a.collision_checks, b.collision_checks);
  EXPECT_EQ(a.local_planner_calls, b.local_planner_calls);
  EXPECT_EQ(a.milestones, b.milestones);
  EXPECT_EQ(a.roadmap_edges, b.roadmap_edges);
  EXPECT_EQ(a.support_vectors, b.support_vectors);
}

TEST(Determinism, SvmpSameSeedSameThreadsSameResult) {
  for (int threads : {1, 2}) {
    SCOPED_TRACE(testing::Message() << threads << " threads");
    auto w1 = makeWorld(gapScenario(0.03, kPlanners), threads);
    auto w2 = makeWorld(gapScenario(0.03, kPlanners), threads);
    const PlanResult a = w1->planner("svmp")->solve(w1->query(), 7);
    const PlanResult b = w2->planner("svmp")->solve(w2->query(), 7);
    ASSERT_TRUE(a.solved()) << a.message;
    expectSameResult(a, b);
    // The same planner object solving again (solve clears) gives the same too.
    auto p = w1->planner("svmp");
    expectSameResult(a, p->solve(w1->query(), 7));
  }
}

// docs/architecture.md, "Determinism": a seed gives the same run on any thread count (per-index slots,
// per-tree generators, milestones inserted in sample order).
TEST(Determinism, OneAndTwoThreadsGiveTheSameRun) {
  for (const char* file : {"thesis_fig4_4.yaml", "forest_200.yaml"})
    for (const char* name : {"svmp", "prm"}) {
      SCOPED_TRACE(std::string(file) + " " + name);
      auto one = makeWorld(test::readScenario(file), 1);
      auto two = makeWorld(test::readScenario(file), 2);
      one->certify();
      two->certify();
      const PlanResult a = one->planner(name)->solve(one->query(), 3);
      const PlanResult b = two->planner(name)->solve(two->query(), 3);
      EXPECT_GT(a.collision_checks, 0u);
      expectSameResult(a, b);
    }
}

TEST(Determinism, PrmSameSeedSameResult) {
  auto w = makeWorld(gapScenario(0.03, kPlanners), 2);
  const PlanResult a = w->planner("prm")->solve(w->query(), 9);
  const PlanResult b = w->planner("prm")->solve(w->query(), 9);
  expectSameResult(a, b);
}

#ifdef SVMP_WITH_OMPL
// SBL's grid projection beyond 2-D (Fig 4.6: 6 joints) follows the run's seed, not OMPL's
// process-wide generator: two worlds, the same seed, the same run.
TEST(Determinism, OmplSblSameSeedSameResultBeyondTwoDimensions) {
  auto w1 = makeWorld(test::readScenario("thesis_fig4_6.yaml"));
  auto w2 = makeWorld(test::readScenario("thesis_fig4_6.yaml"));
  for (std::uint64_t seed : {1, 2, 3}) {
    const PlanResult a = w1->planner("ompl-sbl")->solve(w1->query(), seed);
    const PlanResult b = w2->planner("ompl-sbl")->solve(w2->query(), seed);
    ASSERT_TRUE(a.solved()) << a.message;
    expectSameResult(a, b);
  }
}

// Informed RRT*'s sampler draws through the space's default sampler, ours: its runs repeat for a
// seed, and stopped at the first solution (before any informed draw) it checks what RRT* checks and
// returns its path (differing on the old code: 13,738, 7,163 and 65,396 checks for one seed).
TEST(Determinism, OmplInformedRrtStarRepeatsAndSamplesAsRrtStarUntilItsFirstSolution) {
  auto w1 = makeWorld(test::readScenario("fastron_panda.yaml"));
  auto w2 = makeWorld(test::readScenario("fastron_panda.yaml"));
  for (std::uint64_t seed : {1, 3}) {
    const PlanResult a = w1->planner("ompl-informedrrtstar")->solve(w1->query(), seed);
    const PlanResult b = w2->planner("ompl-informedrrtstar")->solve(w2->query(), seed);
    const PlanResult star = w2->planner("ompl-rrtstar")->solve(w2->query(), seed);
    ASSERT_TRUE(a.solved()) << a.message;
    expectSameResult(a, b);
    EXPECT_EQ(a.collision_checks, star.collision_checks);
    EXPECT_EQ(a.path, star.path);
  }
}
#endif

// Start or goal in collision: a status, not a crash.
void expectInvalidEndpoints(const std::string& planner) {
  auto w = makeWorld(gapScenario(0.03, kPlanners));
  auto p = w->planner(planner);
  cspace::Query q = w->query();
  q.start = Eigen::Vector2d(0.5, 0.2);  // inside the lower wall
  PlanResult r = p->solve(q, 1);
  EXPECT_EQ(r.status, PlanStatus::kInvalidStart) << planner << ": " << r.message;
  EXPECT_TRUE(r.path.empty());
  q = w->query();
  q.goal = Eigen::Vector2d(0.45, 0.9);  // inside the upper wall
  r = p->solve(q, 1);
  EXPECT_EQ(r.status, PlanStatus::kInvalidGoal) << planner << ": " << r.message;
  EXPECT_TRUE(r.path.empty());
  q.start = q.goal = Eigen::Vector2d(0.5, 0.8);
  r = p->solve(q, 1);
  EXPECT_EQ(r.status, PlanStatus::kInvalidStart) << planner << ": both in collision reports the start";
}

TEST(InvalidQueries, SvmpReportsStartAndGoalInCollision) { expectInvalidEndpoints("svmp"); }
TEST(InvalidQueries, PrmReportsStartAndGoalInCollision) { expectInvalidEndpoints("prm"); }
#ifdef SVMP_WITH_OMPL
TEST(InvalidQueries, OmplPrmReportsStartAndGoalInCollision) { expectInvalidEndpoints("ompl-prm"); }
#endif

TEST(InvalidQueries, WrongDimensionIsInvalidInput) {
  auto w = makeWorld(gapScenario(0.03, kPlanners));
  cspace::Query q = w->query();
  q.start = Eigen::Vector3d(0.1, 0.1, 0.1);
  for (const char* name : {"svmp", "prm"})
    EXPECT_EQ(w->planner(name)->solve(q, 1).status, PlanStatus::kInvalidInput) << name;
}

// A planar arm of 33 links: the risk function takes at most 32 joints, so svmp and the local planner
// report invalid input (they had thrown, ending the whole run), while prm takes the query.
TEST(InvalidQueries, TooManyJointsForTheRiskFunctionIsInvalidInput) {
  std::string lengths, zeros, goal;
  for (int i = 0; i < 33; ++i) {
    const std::string sep = i ? ", " : "";
    lengths += sep + "0.1", zeros += sep + "0", goal += sep + (i ? "0" : "1.2");
  }
  auto w = makeWorld("robot: {type: planar_arm, lengths: [" + lengths + "], widths: 0.01}\n"
                     "obstacles:\n  - {shape: box, size: [0.5, 0.5, 1], position: [2.5, 1.5, 0]}\n"
                     "start: [" + zeros + "]\ngoal: [" + goal + "]\nresolution: 0.01\n");
  for (const char* name : {"svmp", "local"}) {
    const PlanResult r = w->planner(name)->solve(w->query(), 1);
    EXPECT_EQ(r.status, PlanStatus::kInvalidInput) << name;
    EXPECT_NE(r.message.find("at most 32 joints; the robot has 33"), std::string::npos) << name << ": " << r.message;
  }
  EXPECT_NE(w->planner("prm")->solve(w->query(), 1).status, PlanStatus::kInvalidInput);
}

// A single query whose straight motion is free and proven needs no roadmap: svmp and prm return it
// before building. Where it is blocked, solve() is build() then query(): the same path and checks
// (the query does not try the straight motion again).
TEST(Planners, RoadmapPlannersAnswerAFreeStraightMotionWithoutABuild) {
  const std::string kOffTheLine =
      "robot: {type: point, bounds: {lower: [0, 0], upper: [1, 1]}}\n"
      "obstacles:\n  - {name: block, shape: box, size: [0.2, 0.2, 1], position: [0.5, 0.5, 0]}\n"
      "start: [0.1, 0.1]\ngoal: [0.1, 0.9]\nresolution: 0.01\n";
  auto w = makeWorld(kOffTheLine);
  w->certify();
  for (const std::string name : {"svmp", "prm"}) {
    auto planner = w->planner(name);
    const PlanResult r = planner->solve(w->query(), 1);
    ASSERT_TRUE(r.solved()) << name << ": " << r.message;
    EXPECT_TRUE(r.certified) << name;
    EXPECT_EQ(r.path.size(), 2u) << name;
    EXPECT_EQ(r.milestones, 0u) << name;
    EXPECT_EQ(r.support_vectors, 0u) << name;
    EXPECT_FALSE(planner->built()) << name;
    EXPECT_LE(r.collision_checks, 100u) << name;  // the 0.8-long motion at resolution 0.01, nothing more
  }
  for (const std::string name : {"svmp", "prm"}) {
    auto gap = makeWorld(gapScenario(0.03, kPlanners));
    gap->certify();
    auto planner = gap->planner(name);
    const PlanResult solved = planner->solve(gap->query(), 4);
    ASSERT_TRUE(solved.solved()) << name << ": " << solved.message;
    EXPECT_GT(solved.path.size(), 2u) << name;
    EXPECT_GT(solved.milestones, 0u) << name;
    const PlanResult built = planner->build(4);
    PlanResult queried = planner->query(gap->query(), 4);
    addBuild(built, queried);
    expectSameResult(solved, queried);
  }
}

TEST(InvalidQueries, SvmpStepsOutOfOrderThrow) {
  auto w = makeWorld(gapScenario(0.03, kPlanners));
  SvmpPlanner svmp(w->context, SvmpOptions{});
  PhaseTimes times;
  EXPECT_THROW(svmp.findBoundaryMilestones(times), std::logic_error);
  EXPECT_THROW(svmp.makeRoadmap(times), std::logic_error);
  EXPECT_THROW(svmp.query(w->query(), 1), std::logic_error);
}

// makePlanner: unknown planners and bad parameters are ScenarioErrors naming the field.
void expectScenarioError(const std::string& planner, std::map<std::string, std::string> values,
                         const std::string& needle) {
  auto w = makeWorld(gapScenario(0.03, kPlanners));
  const cspace::ParameterSet params("test.yaml", "planners." + planner + ".", std::move(values));
  try {
    makePlanner(planner, w->context, params);
    ADD_FAILURE() << planner << ": no ScenarioError (expected one naming '" << needle << "')";
  } catch (const cspace::ScenarioError& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
  }
}

TEST(MakePlanner, UnknownPlannerNamesIt) {
  expectScenarioError("rrt-star", {}, "rrt-star");
  expectScenarioError("ompl-rrtstarr", {}, "ompl-rrtstarr");
}

TEST(MakePlanner, UnknownParameterNamesTheField) {
  expectScenarioError("svmp", {{"sigmaa", "0.1"}}, "planners.svmp.sigmaa");
  expectScenarioError("prm", {{"milestones", "200"}}, "planners.prm.milestones");
#ifdef SVMP_WITH_OMPL
  expectScenarioError("ompl-rrtconnect", {{"samples", "5"}}, "planners.ompl-rrtconnect.samples");
#endif
}

TEST(MakePlanner, OutOfRangeOrMalformedParameterNamesTheField) {
  expectScenarioError("svmp", {{"sigma", "-1"}}, "planners.svmp.sigma");
  expectScenarioError("svmp", {{"samples_per_tree", "0"}}, "planners.svmp.samples_per_tree");
  expectScenarioError("svmp", {{"k", "ten"}}, "planners.svmp.k");
  expectScenarioError("svmp", {{"C", "0"}}, "planners.svmp.C");
  expectScenarioError("prm", {{"samples", "0"}}, "planners.prm.samples");
#ifdef SVMP_WITH_OMPL
  expectScenarioError("ompl-prm", {{"time_limit", "-1"}}, "planners.ompl-prm.time_limit");
#endif
}

TEST(MakePlanner, KnowsEveryListedName) {
  auto w = makeWorld(gapScenario(0.03, kPlanners));
  for (const auto& name : plannerNames()) {
    auto p = makePlanner(name, w->context, cspace::ParameterSet("test.yaml", "planners." + name + ".", {}));
    ASSERT_NE(p, nullptr) << name;
    EXPECT_EQ(p->name(), name);
  }
}

// A lazy edge straight through the wall is checked (at its middle) when A* first uses it, removed from
// the query's roadmap and from the milestones', and the path goes round through the gap on edges now
// checked.
TEST(LazyRoadmap, QueryChecksOnlyItsPathAndRemovesBlockedEdges) {
  auto w = makeWorld(gapScenario(0.03, kPlanners));
  w->certify();
  Roadmap milestones = test::planarRoadmap(w->space, {{0.3, 0.1}, {0.7, 0.1}, {0.3, 0.5}, {0.7, 0.5}, {0.05, 0.95}},
                                           {{0, 1}, {0, 2}, {2, 3}, {3, 1}, {2, 4}}, false);
  const NearestNeighbors nn(milestones.nodes(), w->space.metricScale());
  cspace::Query query;
  query.start = Eigen::Vector2d(0.2, 0.1);
  query.goal = Eigen::Vector2d(0.8, 0.1);
  Roadmap with_query = milestones;
  const QueryOutcome out = queryRoadmap(with_query, nn, w->context, query, 1, &milestones);
  ASSERT_EQ(out.path.size(), 6u);
  EXPECT_TRUE(out.certified);
  EXPECT_EQ(out.lazy_checks, 3) << "the three of the detour (the wall edge falls at its middle); never 2-4";
  for (size_t i = 0; i + 1 < out.path.size(); ++i)
    EXPECT_TRUE(w->certifier.isValid(out.path[i], out.path[i + 1])) << "segment " << i;
  EXPECT_TRUE((out.path[2] - milestones.node(2)).norm() < 1e-12 && (out.path[3] - milestones.node(3)).norm() < 1e-12);
  EXPECT_FALSE(milestones.hasEdge(0, 1)) << "the blocked edge stays in the milestones' roadmap";
  EXPECT_TRUE(milestones.isCertified(0, 2) && milestones.isCertified(2, 3) && milestones.isCertified(3, 1));
  EXPECT_FALSE(milestones.isChecked(2, 4)) << "an edge off the path is left unchecked";
}

// SVMP's lazy roadmap answers with fewer motion checks than the thesis' eager one, certified.
TEST(LazyRoadmap, SvmpChecksFewerMotionsThanEager) {
  const std::string params = "  svmp: {sigma: 0.06, C: 100, step: 0.05, samples_per_tree: 200, k: 10, lazy: ";
  auto lazy = makeWorld(gapScenario(0.03, params + "true}\n"));
  auto eager = makeWorld(gapScenario(0.03, params + "false}\n"));
  lazy->certify();
  eager->certify();
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const PlanResult a = lazy->planner("svmp")->solve(lazy->query(), seed);
    const PlanResult b = eager->planner("svmp")->solve(eager->query(), seed);
    ASSERT_TRUE(a.solved() && b.solved()) << a.message << " / " << b.message;
    EXPECT_TRUE(a.certified);
    EXPECT_TRUE(pathIsValid(*lazy, a.path, lazy->scenario.resolution)) << "seed " << seed;
    EXPECT_LT(a.local_planner_calls, b.local_planner_calls) << "seed " << seed;
  }
}

// A gap of usable width 0.02 in a 0.2 thick wall (0.4% of the square): SVMP's milestones on the
// decision boundary between the wall halves line the gap, so it solves every seed. PRM with a few
// samples is run for comparison only.
TEST(NarrowPassage, SvmpSolvesEverySeed) {
  auto w = makeWorld(gapScenario(0.02,
                                 "  svmp: {sigma: 0.04, C: 100, step: 0.05, samples_per_tree: 300, k: 10}\n"
                                 "  prm: {samples: 300, k: 10}\n"));
  int svmp_solved = 0, prm_solved = 0, strict = 0;
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const PlanResult r = w->planner("svmp")->solve(w->query(), seed);
    EXPECT_TRUE(r.solved()) << "seed " << seed << ": " << r.message;
    if (r.solved()) {
      ++svmp_solved;
      // At the scenario's resolution a segment leaving the gap may clip its corner between two checks
      // (strict_correct in the driver); it must never cross more than one resolution of wall.
      EXPECT_TRUE(pathIsValid(*w, r.path, w->scenario.resolution)) << "seed " << seed;
      strict += pathIsValid(*w, r.path);
    }
    prm_solved += w->planner("prm")->solve(w->query(), seed).solved();
  }
  EXPECT_EQ(svmp_solved, 5);
  std::printf("[ info     ] narrow passage: svmp solved %d/5 (%d strictly valid at 1/4 resolution), "
              "prm (300 samples) %d/5\n", svmp_solved, strict, prm_solved);
}

// The SVMs train on every boundary sample and a share of the interior ones: fewer support vectors,
// the same passage found; a share outside [0, 1] names the field.
TEST(NarrowPassage, SvmpTrainsOnAShareOfTheInterior) {
  const std::string params = "  svmp: {sigma: 0.04, C: 100, step: 0.05, samples_per_tree: 300, k: 10, interior_fraction: ";
  auto all = makeWorld(gapScenario(0.02, params + "1}\n"));
  auto share = makeWorld(gapScenario(0.02, params + "0.1}\n"));
  const PlanResult a = all->planner("svmp")->solve(all->query(), 3);
  const PlanResult b = share->planner("svmp")->solve(share->query(), 3);
  ASSERT_TRUE(a.solved()) << a.message;
  ASSERT_TRUE(b.solved()) << b.message;
  EXPECT_LT(b.support_vectors, a.support_vectors);
  EXPECT_TRUE(pathIsValid(*share, b.path, share->scenario.resolution));
  try {
    makeWorld(gapScenario(0.02, params + "2}\n"))->planner("svmp");
    FAIL() << "interior_fraction 2 accepted";
  } catch (const cspace::ScenarioError& e) {
    EXPECT_NE(std::string(e.what()).find("interior_fraction"), std::string::npos) << e.what();
  }
}

// Each class trained on its neighbourhood with the bias fixed (svm/local_one_vs_rest.hpp): the
// far negatives are no longer support vectors, the same passage is found; an unknown mode names the
// field.
TEST(NarrowPassage, SvmpTrainsEachClassOnItsNeighbourhood) {
  const std::string params = "  svmp: {sigma: 0.04, C: 100, step: 0.05, samples_per_tree: 300, k: 10, training: ";
  auto full = makeWorld(gapScenario(0.02, params + "full}\n"));
  auto local = makeWorld(gapScenario(0.02, params + "neighbourhood}\n"));
  local->certify();
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const PlanResult a = full->planner("svmp")->solve(full->query(), seed);
    const PlanResult b = local->planner("svmp")->solve(local->query(), seed);
    ASSERT_TRUE(a.solved()) << a.message;
    ASSERT_TRUE(b.solved()) << b.message;
    EXPECT_TRUE(b.certified);
    EXPECT_LT(b.support_vectors, a.support_vectors);
    EXPECT_TRUE(pathIsValid(*local, b.path, local->scenario.resolution / 4));
  }
  try {
    makeWorld(gapScenario(0.02, params + "local}\n"))->planner("svmp");
    FAIL() << "training: local accepted";
  } catch (const cspace::ScenarioError& e) {
    EXPECT_NE(std::string(e.what()).find("training"), std::string::npos) << e.what();
  }
}

// Unset samples_per_tree: 200 a tree up to 12 trees, then 2,400 samples spread over the trees, at
// least 20 a tree; a given value stays. On a 6-DoF arm among 30 small boxes (bench/unseen) the build
// then samples at most 2,400 configurations, where 200 a tree samples about 4,500, and it still plans.
TEST(NarrowPassage, SvmpSpreadsItsSampleBudgetOverManyObstacles) {
  const cspace::ConfigurationSpace unit(Eigen::Vector2d::Zero(), Eigen::Vector2d::Ones(), Eigen::Vector2d::Ones());
  EXPECT_EQ(SvmpOptions{}.resolvedFor(unit, 12).samples_per_tree, 200);
  EXPECT_EQ(SvmpOptions{}.resolvedFor(unit, 13).samples_per_tree, 2400 / 13);
  EXPECT_EQ(SvmpOptions{}.resolvedFor(unit, 500).samples_per_tree, 20);
  SvmpOptions given;
  given.samples_per_tree = 300;
  EXPECT_EQ(given.resolvedFor(unit, 500).samples_per_tree, 300);

  auto w = makeWorld(test::readScenario("../unseen/crs6_clutter30.yaml"));
  w->certify();
  const auto planner = w->planner("svmp");
  const PlanResult r = planner->solve(w->query(), 1);
  ASSERT_TRUE(r.solved()) << r.message;
  EXPECT_TRUE(pathIsValid(*w, r.path));
  const auto& spread = dynamic_cast<const SvmpPlanner&>(*planner);
  EXPECT_LE(spread.samples().size(), SvmpOptions::kSampleBudget);
  SvmpOptions full;
  full.samples_per_tree = SvmpOptions::kSamplesPerTree;
  SvmpPlanner each(w->context, full);
  PhaseTimes times;
  ASSERT_TRUE(each.sampleObstacle(1, times));
  EXPECT_GT(each.samples().size(), 3 * SvmpOptions::kSampleBudget / 2);
}

// `classes: auto` above 8 obstacles: one model per obstacle where their neighbourhoods together hold
// under half of one full problem's kernel entries (sparse 3-D obstacles), colours where they cover
// the space (200 boxes in 2-D); a file's `classes: colour` stays. Each plan is valid either way.
TEST(NarrowPassage, SvmpTrainsPerObstacleWhereNeighbourhoodsAreSmall) {
  auto classesOf = [](test::World& w) {
    const auto planner = w.planner("svmp");
    const PlanResult r = planner->solve(w.query(), 1);
    EXPECT_TRUE(r.solved()) << r.message;
    EXPECT_TRUE(pathIsValid(w, r.path));
    return dynamic_cast<const SvmpPlanner&>(*planner).risk()->numClasses();
  };
  std::string sparse = test::readScenario("svpp_3d20_01.yaml");
  EXPECT_EQ(classesOf(*makeWorld(sparse)), 20);
  const std::string svmp_params = "  svmp: {";
  const size_t at = sparse.find(svmp_params);
  ASSERT_NE(at, std::string::npos);
  sparse.insert(at + svmp_params.size(), "classes: colour, ");
  EXPECT_LT(classesOf(*makeWorld(sparse)), 8);
  auto forest = makeWorld(test::readScenario("forest_200.yaml"));
  EXPECT_LT(classesOf(*forest), 30);
}

// Unset sigma and step follow the space's scale (1/40 of the mean range in the metric, sigma twice the
// step); given values stay. The gap family's files give none and still thread a 1 mm gap.
TEST(NarrowPassage, SvmpDerivesSigmaAndStepFromTheSpace) {
  auto big = makeWorld(
      "robot: {type: point, bounds: {lower: [0, 0], upper: [10, 20]}}\n"
      "obstacles:\n"
      "  - {name: a, shape: box, size: [1, 1, 1], position: [3, 3, 0]}\n"
      "start: [1, 1]\n"
      "goal: [9, 9]\n"
      "resolution: 0.01\n"
      "metric_weights: [1.0, 0.5]\n");
  const SvmpOptions derived = SvmpOptions{}.resolvedFor(big->space, 1);
  EXPECT_DOUBLE_EQ(derived.step, (10 * 1.0 + 20 * std::sqrt(0.5)) / 2 / 40);  // metric: sqrt(w) q
  EXPECT_DOUBLE_EQ(derived.sigma, 2 * derived.step);
  SvmpOptions given;
  given.sigma = 0.7;
  EXPECT_DOUBLE_EQ(given.resolvedFor(big->space, 1).sigma, 0.7);
  EXPECT_DOUBLE_EQ(given.resolvedFor(big->space, 1).step, derived.step);
  auto gap = makeWorld(gapScenario(0.001, "  prm: {samples: 100}\n"));
  gap->certify();
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    const PlanResult r = gap->planner("svmp")->solve(gap->query(), seed);
    ASSERT_TRUE(r.solved()) << "seed " << seed << ": " << r.message;
    EXPECT_TRUE(pathIsValid(*gap, r.path)) << "seed " << seed;
  }
}

}  // namespace
}  // namespace svmp::planners
