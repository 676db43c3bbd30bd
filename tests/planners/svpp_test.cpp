// Miura's SVPP (planners/svpp_*): the geometry of its steps (merging, PCA nominal plane, the separating
// line of a symmetric case), that every returned path is certified and densely collision-free,
// determinism for a seed, rejected parameters and robots, and SVM smoothing of a given path.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <numbers>
#include <regex>
#include <sstream>

#include "cspace/certified_motion_validator.hpp"
#include "planners/path_simplifier.hpp"
#include "planners/svpp_planner.hpp"
#include "planners/svpp_smoothing.hpp"
#include "test_world.hpp"

namespace svmp::planners {
namespace {

// A scenario with the certifier the driver uses attached to its planning context.
struct CertifiedWorld {
  std::unique_ptr<test::World> world;
  std::unique_ptr<cspace::CertifiedMotionValidator> certifier;
  PlanningContext context;
  explicit CertifiedWorld(const std::string& yaml)
      : world(test::makeWorld(yaml)),
        certifier(std::make_unique<cspace::CertifiedMotionValidator>(world->checker, world->space,
                                                                     world->scenario.resolution)),
        context{world->space, world->checker, world->validator, 1, certifier.get()} {}
  std::unique_ptr<Planner> planner(const cspace::ParameterSet& params = {}) const {
    return makePlanner("svpp", context, params);
  }
};

const char* kSymmetric =
    "robot: {type: point, bounds: {lower: [0, 0], upper: [2, 2]}}\n"
    "obstacles:\n"
    "  - {name: above, shape: box, size: [0.4, 0.4, 1], position: [1, 1.4, 0]}\n"
    "  - {name: below, shape: box, size: [0.4, 0.4, 1], position: [1, 0.6, 0]}\n"
    "start: [0.2, 1]\ngoal: [1.8, 1]\nresolution: 0.005\n";

// Every point of the path re-checked by the exact checker every resolution / 16.
bool denselyFree(const test::World& w, const std::vector<Eigen::VectorXd>& path) {
  const double step = w.scenario.resolution / 16;
  for (size_t i = 0; i + 1 < path.size(); ++i) {
    const int n = std::max(1, static_cast<int>(std::ceil((path[i + 1] - path[i]).norm() / step)));
    for (int k = 0; k <= n; ++k)
      if (!w.checker.isValid(path[i] + (static_cast<double>(k) / n) * (path[i + 1] - path[i])))
        return false;
  }
  return true;
}

std::string scenarioText(const std::string& file) {
  std::ifstream in(std::string(SVMP_SOURCE_DIR) + "/bench/scenarios/" + file);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

double largestTurn(const std::vector<Eigen::VectorXd>& path) {
  double turn = 0;
  for (size_t i = 1; i + 1 < path.size(); ++i) {
    const Eigen::VectorXd a = (path[i] - path[i - 1]).normalized(),
                          b = (path[i + 1] - path[i]).normalized();
    turn = std::max(turn, std::acos(std::clamp(a.dot(b), -1.0, 1.0)));
  }
  return turn;
}

TEST(SvppTest, SeparatingLineOfSymmetricObstaclesPassesMidway) {
  const CertifiedWorld w(kSymmetric);
  auto planner = w.planner();
  const PlanResult r = planner->solve(w.world->query(), 1);
  ASSERT_TRUE(r.solved()) << r.message;
  EXPECT_TRUE(r.certified);
  const auto& svpp = dynamic_cast<const SvppPlanner&>(*planner);
  ASSERT_EQ(svpp.obstacles().size(), 2u);
  const SvppTrial& chosen = svpp.trace().trials.at(svpp.trace().chosen);
  // The initial pattern: "above" is left of start -> goal (negative), "below" right (positive).
  EXPECT_EQ(chosen.pattern, (Pattern{0, 1}));
  const Eigen::Vector2d midway(1, 1), up(1, 1.15), down(1, 0.85);
  EXPECT_NEAR(chosen.model.decision(midway.data()), 0, 0.05);
  EXPECT_LT(chosen.model.decision(up.data()), 0);
  EXPECT_GT(chosen.model.decision(down.data()), 0);
  // The path crosses x = 1 midway between the obstacles (gap 1.2 .. 0.8) and stays in the gap
  // there.
  for (size_t i = 0; i + 1 < r.path.size(); ++i)
    if ((r.path[i].x() - 1) * (r.path[i + 1].x() - 1) <= 0) {
      EXPECT_NEAR(r.path[i].y(), 1, 0.02);
    }
  EXPECT_LT(largestTurn(r.path), std::numbers::pi / 6);
}

TEST(SvppTest, OverlappingObstaclesMergeAndDropInnerSamples) {
  std::vector<ConvexPart> parts;
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  const auto square = [](double cx, double cy, double side, int id) {
    Eigen::Matrix2Xd v(2, 4);
    const double h = side / 2;
    v << cx - h, cx + h, cx + h, cx - h, cy - h, cy - h, cy + h, cy + h;
    return polygonPart(v, id);
  };
  parts.push_back(square(0, 0, 0.2, 1));       // [-0.1, 0.1]^2
  parts.push_back(square(0.1, 0.05, 0.2, 2));  // [0, 0.2] x [-0.05, 0.15]: overlaps 1
  parts.push_back(square(1, 1, 0.2, 3));       // apart
  parts.push_back(square(1.2, 1, 0.2, 4));     // touches 3 along x = 1.1
  const std::vector<SvppObstacle> merged = mergeObstacles(parts);
  ASSERT_EQ(merged.size(), 2u);
  EXPECT_EQ(merged[0].ids, (std::vector<int>{1, 2}));
  EXPECT_EQ(merged[1].ids, (std::vector<int>{3, 4}));
  // 8 samples per square (vertices, edge midpoints); 1's vertex (0.1, 0.1) and right midpoint (0.1,
  // 0) lie inside 2, 2's vertex (0, -0.05) and left midpoint (0, 0.05) inside 1.
  EXPECT_EQ(merged[0].samples.cols(), 12);
  for (Eigen::Index i = 0; i < merged[0].samples.cols(); ++i)
    EXPECT_GT((merged[0].samples.col(i) - Eigen::Vector2d(0.1, 0.1)).norm(), 1e-9);
  // Touching squares share two vertices and an edge midpoint (nothing is strictly inside): 16 - 3.
  EXPECT_EQ(merged[1].samples.cols(), 13);
  EXPECT_NEAR(merged[1].centroid.x(), 1.1, 1e-12);
  // 3-D: rotated cubes by the separating axis test.
  const Eigen::Matrix3d rotated =
      Eigen::AngleAxisd(std::numbers::pi / 4, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const ConvexPart a = boxPart(Eigen::Vector3d::Zero(), I, Eigen::Vector3d::Constant(0.2));
  EXPECT_TRUE(partsOverlap(
      a, boxPart(Eigen::Vector3d(0.23, 0, 0), rotated, Eigen::Vector3d::Constant(0.2))));
  EXPECT_FALSE(partsOverlap(
      a, boxPart(Eigen::Vector3d(0.25, 0, 0), rotated, Eigen::Vector3d::Constant(0.2))));
  EXPECT_FALSE(partsOverlap(
      a, boxPart(Eigen::Vector3d(0.15, 0.15, 0.15), I, Eigen::Vector3d::Constant(0.09))));
  EXPECT_EQ(
      mergeObstacles({a, boxPart(Eigen::Vector3d(0.2, 0, 0), I, Eigen::Vector3d::Constant(0.2), 2)})
          .front()
          .samples.cols(),
      26 * 2 - 9);  // the shared face's 4 vertices, 4 edge midpoints and centre counted once
}

TEST(SvppTest, NominalPlaneNormalIsThePrincipalDirectionAcrossTheLine) {
  // Vertices spread mostly along (1, 0, 1): its component along the line (x) must not count, so the
  // normal is z, not (1, 0, 1) / sqrt 2.
  Eigen::MatrixXd vertices(3, 6);
  vertices << -2, -1, 0, 1, 2, 3,        //
      0.1, -0.1, -0.1, -0.1, -0.1, 0.1,  // uncorrelated with z
      -2, -1, 0, 1, 2, 3;
  const NominalFrame f = nominalPlane(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0), vertices);
  EXPECT_NEAR(std::abs(f.normal.dot(Eigen::Vector3d::UnitZ())), 1, 1e-9);
  EXPECT_NEAR(f.normal.dot(f.along), 0, 1e-12);
  EXPECT_NEAR(f.across.norm(), 1, 1e-12);
  EXPECT_NEAR(f.across.dot(f.normal), 0, 1e-12);
  EXPECT_GT(f.normal.z(), 0);  // sign convention: largest coordinate positive
  // A diagonal line: the normal is perpendicular to it and follows the spread across it.
  Eigen::MatrixXd spread(3, 2);
  spread << 0, 1, 0, -1, 0, 0;
  const NominalFrame g = nominalPlane(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1), spread);
  EXPECT_NEAR(g.normal.dot(Eigen::Vector3d(1, 1, 1).normalized()), 0, 1e-12);
  EXPECT_NEAR(std::abs(g.normal.dot(Eigen::Vector3d(1, -1, 0).normalized())), 1, 1e-9);
}

TEST(SvppTest, GuidesShiftWhereAnObstacleOfTheOtherClassReachesAcross) {
  const NominalFrame f = nominalLine(Eigen::Vector2d(0, 0), Eigen::Vector2d(2, 0));  // right = -y
  Eigen::Matrix2Xd v(2, 4);
  v << 0.9, 1.1, 1.1, 0.9, -0.3, -0.3, 0.1,
      0.1;  // centroid right of the line, reaches 0.1 to the left
  std::vector<SvppObstacle> obstacles = mergeObstacles({polygonPart(v, 1)});
  TrainingSet set;
  SampleLayout layout;
  addGuideSamples(f, obstacles, Pattern{0}, layout, Eigen::Vector2d(0, -1), Eigen::Vector2d(2, 1),
                  set);
  // Flipped to negative (left): positive guides beside it move to d_g + 0.3 right of the line.
  bool shifted = false;
  for (int i = 0; i < set.size(); ++i) {
    const double t = set.X(0, i), side = f.side(set.X.col(i));
    if (set.y[i] > 0 && t > 0.95 && t < 1.05) {
      EXPECT_NEAR(side, 0.5, 1e-12);
      shifted = true;
    }
    if (set.y[i] > 0 && (t < 0.65 || t > 1.35)) {
      EXPECT_NEAR(side, 0.2, 1e-12);
    }
    if (set.y[i] < 0) {
      EXPECT_NEAR(side, -0.2, 1e-12);  // no positive obstacle reaches the left
    }
  }
  EXPECT_TRUE(shifted);
  EXPECT_EQ(initialPattern(obstacles, f), Pattern{1});
}

TEST(SvppTest, EveryReturnedPathIsCertifiedAndDenselyFree) {
  int solved = 0;
  for (const char* file : {"svpp_2d_01.yaml", "svpp_2d_07.yaml", "svpp_3d10_01.yaml"}) {
    const CertifiedWorld w(scenarioText(file));
    auto planner = w.planner();
    for (std::uint64_t seed : {1, 2}) {
      SCOPED_TRACE(std::string(file) + " seed " + std::to_string(seed));
      const PlanResult r = planner->solve(w.world->query(), seed);
      if (!r.solved()) continue;
      ++solved;
      EXPECT_TRUE(r.certified);
      EXPECT_GT(r.distance_queries, 0u);
      EXPECT_TRUE(test::pathIsValid(*w.world, r.path));
      EXPECT_TRUE(denselyFree(*w.world, r.path));
    }
  }
  EXPECT_GE(solved, 5);
}

TEST(SvppTest, SameSeedSamePath) {
  const CertifiedWorld w(scenarioText("svpp_2d_02.yaml"));
  auto a = w.planner(), b = w.planner();
  const PlanResult first = a->solve(w.world->query(), 7), again = b->solve(w.world->query(), 7);
  ASSERT_TRUE(first.solved()) << first.message;
  ASSERT_EQ(first.path.size(), again.path.size());
  for (size_t i = 0; i < first.path.size(); ++i) EXPECT_EQ(first.path[i], again.path[i]);
  const auto& ta = dynamic_cast<const SvppPlanner&>(*a).trace().trials;
  const auto& tb = dynamic_cast<const SvppPlanner&>(*b).trace().trials;
  ASSERT_EQ(ta.size(), tb.size());
  for (size_t i = 0; i < ta.size(); ++i) EXPECT_EQ(ta[i].pattern, tb[i].pattern);
  // Patterns are distinct and N_p = 20 were tried in 2-D.
  EXPECT_EQ(ta.size(), 20u);
  for (size_t i = 0; i < ta.size(); ++i)
    for (size_t j = i + 1; j < ta.size(); ++j) EXPECT_NE(ta[i].pattern, ta[j].pattern);
}

TEST(SvppTest, BadParametersAndRobotsAreRejected) {
  const CertifiedWorld w(kSymmetric);
  const auto message = [&](const std::string& key, const std::string& value) -> std::string {
    cspace::ParameterSet params("test.yaml", "planners.svpp.", {{key, value}});
    try {
      w.planner(params);
    } catch (const cspace::ScenarioError& e) {
      return e.what();
    }
    return "accepted";
  };
  EXPECT_NE(message("guide_spacing", "-1").find("planners.svpp.guide_spacing"), std::string::npos);
  EXPECT_NE(message("guide_spacing", "-1").find("-1"), std::string::npos);
  EXPECT_NE(message("search_angle_deg", "400").find("400"), std::string::npos);
  EXPECT_NE(message("gamma", "abc").find("abc"), std::string::npos);
  EXPECT_NE(message("guide_distance", "0.01").find("guide_distance (0.01)"), std::string::npos);
  EXPECT_NE(message("step_size", "0.1").find("step_size"), std::string::npos);
  EXPECT_EQ(message("patterns", "5"), "accepted");
  EXPECT_THROW(SvppPlanner(w.context, SvppOptions{.virtual_samples = 0}), std::invalid_argument);
  // Lengths that would fill memory or never end are refused with the file and field. A spacing of
  // 1e-6 asked for 5.7 million guide samples in this 2 x 2 space (1 GB, 42 s).
  EXPECT_NE(message("guide_spacing", "1e-6").find("test.yaml: field 'planners.svpp.guide_spacing': "
                                                  "guide_spacing (1e-06) gives up to"),
            std::string::npos);
  EXPECT_NE(message("step", "1e-9").find("field 'planners.svpp.step': step (1e-09) is below"),
            std::string::npos);
  EXPECT_NE(message("step", "1e-5").find("step (1e-05) is below 1/10000 of the space's diagonal"), std::string::npos);
  EXPECT_EQ(message("step", "3e-4"), "accepted");
  // theta_s steers only the 2-D arc search: in 3-D it would be taken and change nothing.
  const CertifiedWorld w3(scenarioText("svpp_3d10_01.yaml"));
  cspace::ParameterSet angle("test.yaml", "planners.svpp.", {{"search_angle_deg", "90"}});
  try {
    w3.planner(angle);
    ADD_FAILURE() << "search_angle_deg accepted in 3-D";
  } catch (const cspace::ScenarioError& e) {
    EXPECT_NE(std::string(e.what()).find("field 'planners.svpp.search_angle_deg': applies in 2-D only"),
              std::string::npos) << e.what();
  }

  const auto arm = test::makeWorld(
      "robot: {type: planar_arm, lengths: [1, 1], widths: 0.05}\n"
      "obstacles: [{shape: box, size: [0.2, 0.2, 1], position: [1.5, 0.5, 0]}]\n"
      "start: [0, 0]\ngoal: [1, 1]\nresolution: 0.01\n");
  const PlanResult r = makePlanner("svpp", arm->context, {})->solve(arm->query(), 1);
  EXPECT_EQ(r.status, PlanStatus::kInvalidInput);
  EXPECT_NE(r.message.find("point robots"), std::string::npos);
}

// The paper's 2 x 2 field of 0.2 boxes, every length times `scale`.
std::string scaledField(double scale) {
  const double boxes[][2] = {{0.5, 0.4}, {0.7, 1.1}, {1.0, 0.7}, {1.2, 1.5}, {1.45, 0.95}, {0.4, 1.6}};
  std::ostringstream yaml;
  yaml.precision(17);
  yaml << "robot: {type: point, bounds: {lower: [0, 0], upper: [" << 2 * scale << ", " << 2 * scale
       << "]}}\nobstacles:\n";
  for (const auto& b : boxes)
    yaml << "  - {shape: box, size: [" << 0.2 * scale << ", " << 0.2 * scale << ", 1], position: ["
         << b[0] * scale << ", " << b[1] * scale << ", 0]}\n";
  yaml << "start: [" << 0.1 * scale << ", " << 0.1 * scale << "]\ngoal: [" << 1.9 * scale << ", "
       << 1.9 * scale << "]\nresolution: " << 0.005 * scale << "\n";
  return yaml.str();
}

TEST(SvppTest, UnsetLengthsScaleWithTheSpaceSoAScaledProblemGetsTheScaledPath) {
  const CertifiedWorld paper(scaledField(1));
  const cspace::ConfigurationSpace& space = paper.world->space;
  // The paper's values for its 20 obstacles in 2 x 2, and for this sparser field of 6.
  for (const int obstacles : {20, 6}) {
    const SvppOptions resolved = SvppOptions{}.resolvedFor(space, obstacles);
    EXPECT_DOUBLE_EQ(resolved.step, SvppOptions::kPaperStep);
    EXPECT_DOUBLE_EQ(resolved.gamma, SvppOptions::kPaperGamma);
    EXPECT_DOUBLE_EQ(resolved.guide_distance, SvppOptions::kPaperGuideDistance);
  }
  // 80 obstacles in the same space: half the spacing, half the lengths.
  EXPECT_DOUBLE_EQ(SvppOptions{}.resolvedFor(space, 80).step, SvppOptions::kPaperStep / 2);
  EXPECT_DOUBLE_EQ(SvppOptions{}.resolvedFor(space, 80).gamma, 4 * SvppOptions::kPaperGamma);
  EXPECT_EQ(SvppOptions{.step = 0.3}.resolvedFor(space, 80).step, 0.3);  // given, kept
  // So many obstacles that the scaled spacing would exceed the guide samples' bound: wider, valid.
  EXPECT_EQ(SvppOptions{}.resolvedFor(space, 100000000).validateFor(space), "");

  auto planner = paper.planner();
  const PlanResult reference = planner->solve(paper.world->query(), 3);
  ASSERT_TRUE(reference.solved()) << reference.message;
  for (const double scale : {0.01, 40.0}) {
    SCOPED_TRACE(scale);
    const CertifiedWorld w(scaledField(scale));
    EXPECT_NEAR(SvppOptions{}.resolvedFor(w.world->space, 6).step, SvppOptions::kPaperStep * scale,
                1e-12 * scale);
    const PlanResult r = w.planner()->solve(w.world->query(), 3);
    ASSERT_TRUE(r.solved()) << r.message;
    EXPECT_TRUE(r.certified);
    EXPECT_TRUE(denselyFree(*w.world, r.path));
    ASSERT_EQ(r.path.size(), reference.path.size());
    // The same up to the solver's tolerance (eps = 1e-3 on float kernel columns): within 1% of a
    // step. With the paper's absolute values both fields fail, every pattern in collision (0.01) or
    // at the step limit (40).
    for (size_t i = 0; i < r.path.size(); ++i)
      EXPECT_LT((r.path[i] / scale - reference.path[i]).norm(), 0.01 * SvppOptions::kPaperStep)
          << "waypoint " << i;
  }
}

// Merging is quadratic in overlapping obstacles (3,000 took 10 s): a stop ends it, once a part.
TEST(SvppTest, AStopEndsTheMergingOfOverlappingObstacles) {
  std::vector<ConvexPart> parts;
  for (int i = 0; i < 50; ++i) {
    Eigen::Matrix2Xd v(2, 4);
    const double x = 0.01 * i;
    v << x, x + 0.2, x + 0.2, x, 0, 0, 0.2, 0.2;
    parts.push_back(polygonPart(v, i + 1));
  }
  EXPECT_EQ(mergeObstacles(parts).size(), 1u);  // one chain of overlapping squares
  int polls = 0;
  EXPECT_TRUE(mergeObstacles(parts, [&] { return ++polls > 10; }).empty());
  EXPECT_EQ(polls, 11);
}

// A wall across the whole space: no pattern of its one (merged) obstacle gives a path, and the failure
// says why the search ended and why each pattern failed, the counts adding up to the patterns tried.
TEST(SvppTest, AFailureSaysWhichLimitEndedTheSearch) {
  const CertifiedWorld w(
      "robot: {type: point, bounds: {lower: [0, 0], upper: [1, 1]}}\n"
      "obstacles: [{name: wall, shape: box, size: [0.1, 1.2, 1], position: [0.5, 0.5, 0]}]\n"
      "start: [0.1, 0.5]\ngoal: [0.9, 0.5]\nresolution: 0.01\n");
  const PlanResult r = w.planner()->solve(w.world->query(), 1);
  ASSERT_EQ(r.status, PlanStatus::kFailed);
  EXPECT_NE(r.message.find("no path in 2 labelling patterns of 1 merged obstacles (every pattern of the merged obstacles; "),
            std::string::npos) << r.message;
  const std::regex count(": ([0-9]+)[,)]");
  int counted = 0;
  for (auto it = std::sregex_iterator(r.message.begin(), r.message.end(), count); it != std::sregex_iterator(); ++it)
    counted += std::stoi((*it)[1]);
  EXPECT_EQ(counted, 2) << r.message;
}

TEST(SvppTest, TheTimeLimitStopsASurfaceFollowing) {
  const CertifiedWorld w(kSymmetric);
  // Steps of 3e-4 (the finest in this 2 x 2 space): up to 16,000 a pattern. The limit fires at its
  // 100th poll, within the first pattern's following (the pattern loop polls once before it).
  auto planner = w.planner(cspace::ParameterSet("test.yaml", "planners.svpp.", {{"step", "3e-4"}}));
  int polls = 0;
  const PlanResult r = planner->solve(w.world->query(), 1, Termination::when([&] { return ++polls > 100; }));
  EXPECT_EQ(r.status, PlanStatus::kTimeout) << r.message;
  const auto& trials = dynamic_cast<const SvppPlanner&>(*planner).trace().trials;
  ASSERT_FALSE(trials.empty());
  EXPECT_EQ(trials.back().follow.status, FollowStatus::kStopped);
  // The message counts how the patterns ended, as a failure's does (a probe's 31 merged obstacles
  // timed out saying only how many patterns it had tried).
  EXPECT_NE(r.message.find("time limit reached after " + std::to_string(trials.size()) + " patterns ("),
            std::string::npos) << r.message;
  EXPECT_NE(r.message.find(std::string(followStatusName(FollowStatus::kStopped)) + ": 1)"), std::string::npos)
      << r.message;
}

TEST(SvppTest, ATimeLimitAfterAPathReturnsItWithAWarning) {
  const CertifiedWorld w(kSymmetric);
  auto planner = w.planner(cspace::ParameterSet("test.yaml", "planners.svpp.", {}));
  const auto& trials = dynamic_cast<const SvppPlanner&>(*planner).trace().trials;
  // The limit fires once the first pattern has given a path, before the others are tried.
  const PlanResult r = planner->solve(
      w.world->query(), 1, Termination::when([&] { return !trials.empty() && trials.front().valid; }));
  ASSERT_EQ(trials.size(), 1u);
  EXPECT_EQ(r.status, PlanStatus::kSolved) << r.message;
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_NE(r.warnings[0].find("time limit reached after 1 patterns"), std::string::npos) << r.warnings[0];
}

TEST(SvppTest, SmoothingFollowsTheSeparatingLineOfAGivenPath) {
  const CertifiedWorld w(kSymmetric);
  // A certified zig-zag through the gap between the two obstacles, with a turn of 88 deg.
  const std::vector<Eigen::VectorXd> zigzag = {Eigen::Vector2d(0.2, 1), Eigen::Vector2d(0.4, 1.15),
                                               Eigen::Vector2d(0.6, 0.9),
                                               Eigen::Vector2d(1.5, 1.05), Eigen::Vector2d(1.8, 1)};
  ASSERT_GT(largestTurn(zigzag), 1.5);
  for (size_t i = 0; i + 1 < zigzag.size(); ++i)
    ASSERT_TRUE(w.certifier->isValid(zigzag[i], zigzag[i + 1]));
  const SvmSmoothing s =
      smoothPathBySvm(zigzag, w.world->checker, *w.certifier, w.world->space, SvppOptions{});
  ASSERT_TRUE(s.smoothed) << s.why;
  EXPECT_EQ(s.path.front(), zigzag.front());
  EXPECT_EQ(s.path.back(), zigzag.back());
  EXPECT_TRUE(denselyFree(*w.world, s.path));
  EXPECT_LT(largestTurn(s.path), std::numbers::pi / 6);
  // The obstacles are labelled by the given path's side, so the line passes midway between them.
  for (size_t i = 0; i + 1 < s.path.size(); ++i)
    if ((s.path[i].x() - 1) * (s.path[i + 1].x() - 1) <= 0) {
      EXPECT_NEAR(s.path[i].y(), 1, 0.03);
    }
  // Another robot: the path is kept and the reason given.
  const auto arm = test::makeWorld(
      "robot: {type: planar_arm, lengths: [1, 1], widths: 0.05}\nstart: [0, 0]\ngoal: [1, "
      "1]\nresolution: 0.01\n");
  const cspace::CertifiedMotionValidator arm_certifier(arm->checker, arm->space, 0.01);
  const std::vector<Eigen::VectorXd> arm_path = {Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 1)};
  const SvmSmoothing kept =
      smoothPathBySvm(arm_path, arm->checker, arm_certifier, arm->space, SvppOptions{});
  EXPECT_FALSE(kept.smoothed);
  EXPECT_EQ(kept.path, arm_path);
}

// A probe's corridor: a straight path along its centreline already has the largest margin there is,
// and the open ends bend the separating line towards the walls (clearance 0.10 -> 0.017 before the
// smoothing compared them). Smoothing never returns a path with less clearance than it was given.
TEST(SvppTest, SmoothingKeepsAPathWhoseClearanceItWouldLower) {
  const CertifiedWorld w(
      "robot: {type: point, bounds: {lower: [0, 0], upper: [10, 1]}}\n"
      "obstacles:\n"
      "  - {name: top, shape: box, size: [8, 0.4, 1.0], position: [5, 0.8]}\n"
      "  - {name: bottom, shape: box, size: [8, 0.4, 1.0], position: [5, 0.2]}\n"
      "start: [0.2, 0.5]\ngoal: [9.8, 0.5]\nresolution: 0.01\n");
  const std::vector<Eigen::VectorXd> centreline = {Eigen::Vector2d(0.2, 0.5), Eigen::Vector2d(9.8, 0.5)};
  const double step = 0.01 / 4;
  const double given = minClearance(centreline, w.world->checker, w.world->space, step);
  ASSERT_NEAR(given, 0.1, 1e-6);
  const SvmSmoothing s = smoothPathBySvm(centreline, w.world->checker, *w.certifier, w.world->space, SvppOptions{});
  EXPECT_GE(minClearance(s.path, w.world->checker, w.world->space, step), given);
  EXPECT_FALSE(s.smoothed);
  EXPECT_EQ(s.path, centreline);
  EXPECT_NE(s.why.find("clearance"), std::string::npos) << s.why;
}

// Surface following against its definition (Miura 2006 secs. III-B-5 and IV-B-4), on a model whose
// V = 0 is known: one support vector at c with coefficient 1 and bias -1/2 gives V = 0 on the circle
// (sphere) of radius sqrt(ln 2 / gamma) about c. Every waypoint between start and goal lies on it,
// a step d_s from the one before, and the walk reaches the goal.
svm::BinaryModel roundSurface(const Eigen::VectorXd& centre, double radius) {
  return svm::BinaryModel(centre, Eigen::VectorXd::Ones(1), -0.5, svm::Kernel::rbf(std::log(2.0) / (radius * radius)));
}

TEST(SurfaceFollowing, TwoDimensionsWalkTheCircleVEqualsZero) {
  const Eigen::Vector2d centre(1, 1);
  const double radius = 0.5;
  const svm::BinaryModel model = roundSurface(centre, radius);
  SurfaceFollowing o;
  o.step = 0.05;
  o.lower = Eigen::Vector2d(-1, -1);
  o.upper = Eigen::Vector2d(3, 3);
  const Eigen::Vector2d start = centre + Eigen::Vector2d(-radius, 0), goal = centre + Eigen::Vector2d(0, radius);
  // Heading along the tangent towards the goal (a quarter turn clockwise round the circle).
  const FollowResult r = followSurface2d(model, start, goal, Eigen::Vector2d(0, 1), o);
  ASSERT_TRUE(r.reached()) << followStatusName(r.status);
  ASSERT_GT(r.path.size(), 10u);  // a quarter of the circle is 0.79 long: about 16 steps
  EXPECT_LT(r.path.size(), 20u);
  for (size_t i = 1; i + 1 < r.path.size(); ++i) {
    EXPECT_NEAR((r.path[i] - centre).norm(), radius, 1e-4) << "waypoint " << i;
    EXPECT_NEAR((r.path[i] - r.path[i - 1]).norm(), o.step, 1e-9) << "waypoint " << i;
    // Clockwise from the left through the top: never below the centre, x never decreasing.
    EXPECT_GE(r.path[i].y(), centre.y() - 1e-9);
    EXPECT_GE(r.path[i].x(), r.path[i - 1].x() - 1e-9);
  }
  EXPECT_TRUE(r.path.back() == goal);
}

TEST(SurfaceFollowing, ThreeDimensionsWalkTheSphereVEqualsZero) {
  const Eigen::Vector3d centre(1, 1, 1);
  const double radius = 0.5;
  const svm::BinaryModel model = roundSurface(centre, radius);
  SurfaceFollowing o;
  o.step = 0.05;
  o.lower = Eigen::Vector3d::Constant(-1);
  o.upper = Eigen::Vector3d::Constant(3);
  const Eigen::Vector3d start = centre + Eigen::Vector3d(-radius, 0, 0);
  const Eigen::Vector3d goal = centre + radius * Eigen::Vector3d(0, 1, 1).normalized();
  const FollowResult r = followSurface3d(model, start, goal, [&](const Eigen::VectorXd&) { return goal; }, o);
  ASSERT_TRUE(r.reached()) << followStatusName(r.status);
  // The great circle between them is a quarter turn, 0.79 long; the walk may wander but not far.
  EXPECT_GT(r.path.size(), 10u);
  EXPECT_LT(r.length, 1.5 * 0.5 * std::numbers::pi * radius);
  for (size_t i = 1; i + 1 < r.path.size(); ++i) {
    EXPECT_NEAR((r.path[i] - centre).norm(), radius, 1e-3) << "waypoint " << i;
    EXPECT_NEAR((r.path[i] - r.path[i - 1]).norm(), o.step, 0.2 * o.step) << "waypoint " << i;
  }
  EXPECT_TRUE(r.path.back() == goal);
}

}  // namespace
}  // namespace svmp::planners
