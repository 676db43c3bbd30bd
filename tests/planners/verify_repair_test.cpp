// Verify and Repair (planners/verify_repair.hpp): paths planned on a stale Fastron proxy (trained before
// the wall moved, as after an unnoticed obstacle move) are certified on the exact checker and re-checked
// densely; a path straight through a wall is
// repaired around it; without a repairable stretch the query fails instead of returning a path.
#include <gtest/gtest.h>

#include <cmath>

#include "cspace/certified_motion_validator.hpp"
#include "cspace/fastron_checker.hpp"
#include "planners/verify_repair.hpp"
#include "tests/planners/test_world.hpp"

namespace svmp::planners {
namespace {

struct ProxyWorld {
  const std::string yaml = test::gapScenario(0.15, "  ompl-rrtconnect: {}\n");
  std::unique_ptr<test::World> w = test::makeWorld(yaml);
  std::unique_ptr<test::World> stale;  // the same wall at x = 0.25 instead of 0.5
  cspace::CertifiedMotionValidator certifier{w->checker, w->space, w->scenario.resolution};
  PlanningContext exact{w->space, w->checker, w->validator, 1, &certifier};
  PathRepairer repairer{exact};
  std::unique_ptr<cspace::FastronChecker> proxy;
  std::unique_ptr<cspace::DiscreteMotionValidator> proxy_validator;
  ProxyWorld() {
    std::string moved = yaml;
    for (size_t at; (at = moved.find("position: [0.5,")) != std::string::npos;) moved.replace(at, 15, "position: [0.25,");
    stale = test::makeWorld(moved);
    proxy = std::make_unique<cspace::FastronChecker>(
        w->scenario.robot, cspace::FastronCheckerOptions::defaults(cspace::FastronFeatures::kJoints));
    proxy->train(stale->checker, 1, {w->query().start, w->query().goal});
    proxy_validator = std::make_unique<cspace::DiscreteMotionValidator>(*proxy, w->space, w->scenario.resolution);
  }
  PlanningContext context() const {
    return PlanningContext{w->space, *proxy, *proxy_validator, 1, &certifier, &repairer};
  }
};

TEST(VerifyRepair, PathsOnAStaleProxyAreCertifiedOnTheExactChecker) {
  const ProxyWorld pw;
  const PlanningContext context = pw.context();
  int solved = 0, repaired = 0;
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    auto planner = makePlanner("ompl-rrtconnect", context, cspace::ParameterSet());
    const PlanResult r = planner->solve(pw.w->query(), seed, Termination::after(30));  // a guard against hangs only
    if (!r.solved()) {
      ADD_FAILURE() << "seed " << seed << ": " << planStatusName(r.status) << " " << r.message;
      continue;
    }
    ++solved;
    repaired += r.repaired_stretches;
    EXPECT_TRUE(r.certified);
    EXPECT_TRUE(test::pathIsValid(*pw.w, r.path)) << "seed " << seed;
    for (size_t i = 0; i + 1 < r.path.size(); ++i) EXPECT_TRUE(pw.certifier.isValid(r.path[i], r.path[i + 1]));
  }
  EXPECT_GE(solved, 6);
  EXPECT_GT(repaired, 0) << "the stale proxy never needed a repair: the test would not exercise it";
}

// Whether a query is valid is the exact checker's call: a proxy (here the stale world's checker) that
// predicts a free goal in collision must not make a planner call the query invalid.
TEST(VerifyRepair, AProxysWrongEndpointPredictionDoesNotMakeTheQueryInvalid) {
  const ProxyWorld pw;
  Eigen::VectorXd goal;
  for (double x = 0; x <= 1 && goal.size() == 0; x += 0.01)
    for (double y = 0; y <= 1; y += 0.01) {
      const Eigen::Vector2d q(x, y);
      if (pw.stale->checker.check(q) != cspace::kFree && pw.w->checker.check(q) == cspace::kFree) {
        goal = q;
        break;
      }
    }
  ASSERT_EQ(goal.size(), 2) << "test premise: the stale wall covers free space of the real world";
  const cspace::Query query{pw.w->query().start, goal, {}};
  const PlanningContext on_proxy{pw.w->space, pw.stale->checker, pw.stale->validator, 1, &pw.certifier, &pw.repairer};
  auto planner = makePlanner("prm", on_proxy, cspace::ParameterSet());
  const PlanResult r = planner->solve(query, 1, Termination::after(2));
  EXPECT_NE(r.status, PlanStatus::kInvalidGoal) << r.message;
  // OMPL's planners take the proxy's word for a start; their failure says whose word it was.
  const cspace::Query from_there{goal, pw.w->query().start, {}};
  const PlanResult rrt = makePlanner("ompl-rrtconnect", on_proxy, cspace::ParameterSet())->solve(from_there, 1);
  EXPECT_FALSE(rrt.solved());
  EXPECT_NE(rrt.message.find("predicts the start in collision; the exact checker has it free"), std::string::npos)
      << rrt.message;
  // Without a repairer the checker is the exact one: then its word is the query's validity.
  const PlanningContext exact_stale{pw.w->space, pw.stale->checker, pw.stale->validator, 1};
  EXPECT_EQ(makePlanner("prm", exact_stale, cspace::ParameterSet())->solve(query, 1).status, PlanStatus::kInvalidGoal);
}

// The OMPL planners added for the Fastron experiments, on the exact checker with verify and repair as
// the driver runs them: each solves the gap and returns a certified path that a dense re-check accepts.
TEST(VerifyRepair, EveryOmplTreePlannerReturnsCertifiedPaths) {
  const auto w = test::makeWorld(test::gapScenario(0.15, "  ompl-rrt: {}\n"));
  const cspace::CertifiedMotionValidator certifier(w->checker, w->space, w->scenario.resolution);
  const PlanningContext repair_context{w->space, w->checker, certifier, 1, &certifier};
  const PathRepairer repairer(repair_context);
  const PlanningContext context{w->space, w->checker, w->validator, 1, &certifier, &repairer};
  for (const char* name : {"ompl-rrt", "ompl-sbl", "ompl-rrtstar", "ompl-fmt", "ompl-informedrrtstar"}) {
    for (std::uint64_t seed = 1; seed <= 2; ++seed) {
      const PlanResult r = makePlanner(name, context, cspace::ParameterSet())->solve(w->query(), seed, Termination::after(10));
      ASSERT_TRUE(r.solved()) << name << " seed " << seed << ": " << r.message;
      EXPECT_TRUE(r.certified) << name;
      EXPECT_TRUE(test::pathIsValid(*w, r.path)) << name << " seed " << seed;
    }
  }
}

TEST(VerifyRepair, AStraightPathThroughTheWallIsReplannedAroundIt) {
  const ProxyWorld pw;
  std::vector<Eigen::VectorXd> path = {pw.w->query().start, Eigen::Vector2d(0.5, 0.2), pw.w->query().goal};
  RepairStats stats;
  std::string why;
  ASSERT_TRUE(pw.repairer.verifyAndRepair(path, "ompl-rrtconnect", 3, Termination::after(10), stats, why)) << why;
  EXPECT_EQ(stats.invalid_stretches, 1);  // the waypoint inside the wall and both segments around it
  EXPECT_GT(stats.exact_checks, 0u);
  EXPECT_TRUE(test::pathIsValid(*pw.w, path));
}

TEST(VerifyRepair, AStretchThatCannotBeRepairedFailsTheQuery) {
  const ProxyWorld pw;
  std::vector<Eigen::VectorXd> path = {pw.w->query().start, Eigen::Vector2d(0.5, 0.2), pw.w->query().goal};
  RepairStats stats;
  std::string why;
  // A stop condition that has already fired: the repair planner cannot run.
  EXPECT_FALSE(pw.repairer.verifyAndRepair(path, "ompl-rrtconnect", 3, Termination::when([] { return true; }), stats, why));
  EXPECT_NE(why.find("repair of waypoints 0 to 2 with ompl-rrtconnect failed"), std::string::npos) << why;
  EXPECT_EQ(path.size(), 3u);  // untouched
}

// OMPL plans on q * sqrt(w). With weights other than 1, a goal at a joint limit came back one unit in
// the last place beyond it (2.8973 * sqrt(2) / sqrt(2) = 2.8973000000000004): OMPL's planners called
// the goal invalid and FMT* crashed on it; every OMPL path also began and ended 1 ulp off the query.
TEST(VerifyRepair, OmplPlansFromAndToTheQuerysOwnEndsAtTheJointLimits) {
  const auto w = test::makeWorld(R"(robot: {type: planar_arm, lengths: [1, 1], widths: 0.05,
  limits: {lower: [-2.8973, -2.8973], upper: [2.8973, 2.8973]}}
obstacles: [{shape: box, size: [0.2, 0.2, 1], position: [5, 5, 0]}]
start: [-0.45961961305550414, -0.1349988594824283]
goal: [2.8973, -1.3408615646987703]
resolution: 0.01
metric_weights: [2, 0.5]
)");
  ASSERT_NE(w->query().goal[0] * std::sqrt(2.0) / std::sqrt(2.0), w->query().goal[0]) << "test premise";
  const cspace::CertifiedMotionValidator certifier(w->checker, w->space, w->scenario.resolution);
  const PlanningContext repair_context{w->space, w->checker, certifier, 1, &certifier};
  const PathRepairer repairer(repair_context);
  const PlanningContext context{w->space, w->checker, w->validator, 1, &certifier, &repairer};
  for (const char* name : {"ompl-rrtconnect", "ompl-prm", "ompl-fmt"}) {
    const PlanResult r = makePlanner(name, context, cspace::ParameterSet())->solve(w->query(), 1, Termination::after(10));
    ASSERT_TRUE(r.solved()) << name << ": " << planStatusName(r.status) << " " << r.message;
    EXPECT_EQ(r.path.front(), w->query().start) << name;
    EXPECT_EQ(r.path.back(), w->query().goal) << name;
    EXPECT_TRUE(test::pathIsValid(*w, r.path)) << name;
  }
}

}  // namespace
}  // namespace svmp::planners
