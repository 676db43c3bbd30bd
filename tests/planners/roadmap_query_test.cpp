// A roadmap query (planners/roadmap_builder.cpp): the straight motion first, endpoint edges proven when
// made, provenPath; SVMP's trees, repair on fastron_panda's random queries, and trees before the build.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <regex>

#include "bench/experiments/experiment.hpp"
#include "planners/roadmap_builder.hpp"
#include "planners/svmp_planner.hpp"
#include "test_world.hpp"

namespace svmp::planners {
namespace {

using test::gapScenario;
using test::makeWorld;
using test::planarRoadmap;

const std::string kPlanners = "  prm: {samples: 100, k: 5}\n";

// Every segment of `path` re-checked at a quarter of the scenario's resolution.
void expectFreeAtQuarterResolution(const test::World& w, const std::vector<Eigen::VectorXd>& path,
                                   const std::string& what) {
  Eigen::VectorXd q(w.space.dim());
  for (size_t i = 0; i + 1 < path.size(); ++i) {
    const int steps = static_cast<int>(std::ceil(4 * w.space.distance(path[i], path[i + 1]) / w.scenario.resolution));
    for (int s = 0; s <= steps; ++s) {
      w.space.interpolate(path[i], path[i + 1], static_cast<double>(s) / std::max(steps, 1), q);
      ASSERT_TRUE(w.checker.isValid(q)) << what << " segment " << i << " step " << s;
    }
  }
}

// A point robot in the unit square and a wall x in [0.4, 0.6] across it, of two overlapping boxes:
// no path joins its two sides.
std::string closedWall(double resolution) {
  return "robot: {type: point, bounds: {lower: [0, 0], upper: [1, 1]}}\n"
         "obstacles:\n"
         "  - {name: wall_lower, shape: box, size: [0.2, 0.65, 1.0], position: [0.5, 0.225, 0]}\n"
         "  - {name: wall_upper, shape: box, size: [0.2, 0.65, 1.0], position: [0.5, 0.775, 0]}\n"
         "start: [0.1, 0.1]\n"
         "goal: [0.9, 0.9]\n"
         "resolution: " + std::to_string(resolution) + "\n";
}

// A point robot in the unit square with one wall 0.01 thick at x = 0.55, y in [0.4, 0.6], checked at
// resolution 0.1: a segment crossing the wall between two checks passes the sampled validator, and
// only the proof refuses it.
const std::string kThinWall =
    "name: thin_wall\n"
    "robot: {type: point, bounds: {lower: [0, 0], upper: [1, 1]}}\n"
    "obstacles:\n"
    "  - {name: wall, shape: box, size: [0.01, 0.2, 1.0], position: [0.55, 0.5, 0]}\n"
    "start: [0.5, 0.5]\n"
    "goal: [0.9, 0.9]\n"
    "resolution: 0.1\n"
    "planners:\n" +
    kPlanners;

TEST(RoadmapQuery, AFreeProvenStraightMotionIsThePathWithoutEndpointEdges) {
  auto w = makeWorld(gapScenario(0.03, kPlanners));
  w->certify();
  Roadmap milestones = planarRoadmap(w->space, {{0.2, 0.2}, {0.3, 0.5}, {0.8, 0.5}}, {{0, 1}}, true);
  const NearestNeighbors nn(milestones.nodes(), w->space.metricScale());
  cspace::Query left;  // both left of the wall: the straight motion is free
  left.start = Eigen::Vector2d(0.1, 0.1);
  left.goal = Eigen::Vector2d(0.3, 0.8);
  Roadmap with_query = milestones;
  const QueryOutcome out = queryRoadmap(with_query, nn, w->context, left, 2, &milestones);
  ASSERT_EQ(out.path.size(), 2u);
  EXPECT_TRUE(out.certified);
  EXPECT_EQ(with_query.neighbours(out.start_node).size(), 1u) << "the start connects to the goal only";
  EXPECT_EQ(with_query.neighbours(out.goal_node).size(), 1u);
  EXPECT_GT(out.certify_ms, 0.0);

  cspace::Query across;  // through the wall: blocked, so the endpoints join the roadmap
  across.start = Eigen::Vector2d(0.2, 0.1);
  across.goal = Eigen::Vector2d(0.8, 0.1);
  Roadmap again = milestones;
  const QueryOutcome blocked = queryRoadmap(again, nn, w->context, across, 2, &milestones);
  EXPECT_TRUE(blocked.path.empty()) << "the roadmap has no way through the gap";
  EXPECT_GE(again.neighbours(blocked.start_node).size(), 1u);
  EXPECT_FALSE(again.hasEdge(blocked.start_node, blocked.goal_node));
}

TEST(RoadmapQuery, EndpointEdgesThatPassTheSampledCheckButNotTheProofAreNotMade) {
  auto w = makeWorld(kThinWall);
  // The first node beyond the wall, 0.1 from the start.
  Roadmap milestones = planarRoadmap(w->space, {{0.6, 0.5}, {0.9, 0.8}}, {{0, 1}}, true);
  const NearestNeighbors nn(milestones.nodes(), w->space.metricScale());
  for (int i = 0; i < 2; ++i) {
    ASSERT_TRUE(w->validator.isValid(w->query().start, milestones.node(i))) << "sampled check misses the wall";
    ASSERT_FALSE(w->certifier.isValid(w->query().start, milestones.node(i))) << "the proof sees it";
  }
  ASSERT_TRUE(w->validator.isValid(w->query().start, w->query().goal));
  ASSERT_FALSE(w->certifier.isValid(w->query().start, w->query().goal));

  // Without a certifier the sampled edges make a path (uncertified); with one, the start stays alone.
  Roadmap sampled = milestones;
  const QueryOutcome unproven = queryRoadmap(sampled, nn, w->context, w->query(), 2);
  EXPECT_FALSE(unproven.path.empty());
  EXPECT_FALSE(unproven.certified);
  w->certify();
  Roadmap proven = milestones;
  const QueryOutcome out = queryRoadmap(proven, nn, w->context, w->query(), 2);
  EXPECT_TRUE(out.path.empty());
  EXPECT_TRUE(proven.neighbours(out.start_node).empty()) << "no edge through the wall";
  EXPECT_FALSE(proven.connected(out.start_node, out.goal_node));
  ASSERT_EQ(proven.neighbours(out.goal_node).size(), 1u);
  EXPECT_TRUE(proven.isCertified(out.goal_node, proven.neighbours(out.goal_node).front().to))
      << "an endpoint's edge is proven when made";
}

// provenPath on the thin wall: the short route's first edge passes the sampled check but not the
// proof; it is removed (from the shared roadmap too) and the path goes round the wall, every edge
// proven (not under a time limit that has fired). With the long way cut as well, there is no path
// and the two fall apart.
TEST(RoadmapQuery, ProvenPathRemovesEdgesTheProofRefusesAndGoesRound) {
  auto w = makeWorld(kThinWall);
  w->certify();
  Roadmap milestones = planarRoadmap(w->space, {{0.5, 0.5}, {0.62, 0.5}, {0.9, 0.9}, {0.5, 0.7}, {0.6, 0.7}},
                                     {{0, 1}, {1, 2}, {0, 3}, {3, 4}, {4, 2}}, false);
  Roadmap copy = milestones;
  int checks = 0;
  double certify_ms = 0;
  {
    // Under a time limit that fires (cspace::MotionStopScope) after the search's first poll, during the
    // proofs, it gives up with no path and removes no edge on the limit's account: a later query on
    // the shared roadmap still has them all.
    Roadmap shared = milestones, searched = milestones;
    int fired_checks = 0;
    const cspace::MotionStopScope fired([polls = 0]() mutable { return ++polls > 1; });
    EXPECT_TRUE(provenPath(searched, 0, 2, w->context, &shared, fired_checks, certify_ms).empty());
    EXPECT_EQ(fired_checks, 2) << "the first path's sampled checks ran; its first proof failed under the limit";
    EXPECT_EQ(shared.numEdges(), 5);
    EXPECT_EQ(searched.numEdges(), 5);
  }
  const std::vector<int> path = provenPath(copy, 0, 2, w->context, &milestones, checks, certify_ms);
  EXPECT_EQ(path, (std::vector<int>{0, 3, 4, 2}));
  EXPECT_FALSE(copy.hasEdge(0, 1));
  EXPECT_FALSE(milestones.hasEdge(0, 1)) << "removed from the shared roadmap too";
  for (size_t i = 0; i + 1 < path.size(); ++i) {
    EXPECT_TRUE(milestones.isCertified(path[i], path[i + 1]));
    EXPECT_TRUE(w->certifier.isValid(copy.node(path[i]), copy.node(path[i + 1])));
  }
  EXPECT_GT(certify_ms, 0.0);
  EXPECT_EQ(checks, 5) << "the sampled pass checks the whole first path, then the detour's three";

  // Moved to (0.6, 0.5), node 1's edge from 0 has its middle in the wall; moved to (0.7, 0.5), its
  // quarter point. The screening passes remove it before any edge's full check (which it would pass,
  // at resolution 0.1), so only the detour's three are checked.
  for (const double x : {0.6, 0.7}) {
    Roadmap screened = planarRoadmap(w->space, {{0.5, 0.5}, {x, 0.5}, {0.9, 0.9}, {0.5, 0.7}, {0.6, 0.7}},
                                     {{0, 1}, {1, 2}, {0, 3}, {3, 4}, {4, 2}}, false);
    ASSERT_TRUE(w->validator.isValid(screened.node(0), screened.node(1)));
    int screened_checks = 0;
    EXPECT_EQ(provenPath(screened, 0, 2, w->context, nullptr, screened_checks, certify_ms), path) << x;
    EXPECT_EQ(screened_checks, 3) << x;
  }

  // The eager pass after a failed lazy query does not make again an edge a query removed (0-1 passes
  // its sampled check), though 1, cut off from 2 here, has 0 as its nearest node in another component.
  EXPECT_TRUE(milestones.isBlocked(1, 0));
  Roadmap eager = milestones;
  eager.dropUnchecked();
  eager.removeEdge(1, 2);
  const NearestNeighbors nn(eager.nodes(), w->space.metricScale());
  connectMilestones(eager, nn, w->context, 4);
  EXPECT_FALSE(eager.hasEdge(0, 1));
  EXPECT_TRUE(eager.connected(0, 1)) << "1 joins through another neighbour";

  Roadmap cut = milestones;
  cut.removeEdge(3, 4);
  EXPECT_TRUE(provenPath(cut, 0, 2, w->context, nullptr, checks, certify_ms).empty());
  EXPECT_FALSE(cut.connected(0, 2));
}

// connectShortestFirst against brute force, with every pair a candidate (k above the node count): the
// edges it makes are a minimum spanning forest of the free pairs, so its components are those of all
// free pairs and its total length is Prim's over them.
// provenPath past a few dozen searches: a wall x in [0.4, 0.6] below y = 0.8, and beside it two
// columns of 10 nodes (y 0.70-0.79) joined by 100 unchecked edges straight through the wall, with a
// checked way round its top. The searches try the crossing edges shortest first, one removal each,
// until every unchecked edge's midpoint is checked at once. That removes too a crossing edge far
// below (y = 0.1), which no search would have tried: the way round is shorter than any path through it.
TEST(RoadmapQuery, ProvenPathScreensEveryMidpointAfterManySearches) {
  auto w = makeWorld(
      "robot: {type: point, bounds: {lower: [0, 0], upper: [1, 1]}}\n"
      "obstacles:\n"
      "  - {name: wall, shape: box, size: [0.2, 0.8, 1.0], position: [0.5, 0.4, 0]}\n"
      "start: [0.3, 0.7]\n"
      "goal: [0.7, 0.7]\n"
      "resolution: 0.01\n");
  Roadmap roadmap;
  constexpr int kRows = 10;
  for (int side = 0; side < 2; ++side)
    for (int i = 0; i < kRows; ++i) roadmap.addNode(Eigen::Vector2d(side ? 0.7 : 0.3, 0.70 + 0.01 * i));
  const int top_left = roadmap.addNode(Eigen::Vector2d(0.3, 0.9)), top_right = roadmap.addNode(Eigen::Vector2d(0.7, 0.9));
  const int low_left = roadmap.addNode(Eigen::Vector2d(0.3, 0.1)), low_right = roadmap.addNode(Eigen::Vector2d(0.7, 0.1));
  const auto link = [&](int a, int b, bool checked) {
    roadmap.addEdge(a, b, w->space.distance(roadmap.node(a), roadmap.node(b)), checked);
  };
  for (int i = 0; i < kRows; ++i) {
    if (i + 1 < kRows) link(i, i + 1, true), link(kRows + i, kRows + i + 1, true);
    for (int j = 0; j < kRows; ++j) link(i, kRows + j, false);
  }
  link(kRows - 1, top_left, true), link(top_left, top_right, true), link(top_right, 2 * kRows - 1, true);
  link(0, low_left, true), link(kRows, low_right, true), link(low_left, low_right, false);
  int checks = 0;
  double certify_ms = 0;
  const std::vector<int> path = provenPath(roadmap, 0, kRows, w->context, nullptr, checks, certify_ms);
  ASSERT_FALSE(path.empty());
  EXPECT_TRUE(std::find(path.begin(), path.end(), top_left) != path.end()) << "round the top";
  EXPECT_FALSE(roadmap.hasEdge(low_left, low_right)) << "screened with every other unchecked edge";
  Eigen::VectorXd mid(2);
  for (int u = 0; u < roadmap.numNodes(); ++u)
    for (const Edge& e : roadmap.neighbours(u)) {
      w->space.interpolate(roadmap.node(u), roadmap.node(e.to), 0.5, mid);
      EXPECT_TRUE(w->checker.isValid(mid)) << "an edge through the wall is left: " << u << "-" << e.to;
    }
}

TEST(RoadmapBuilder, ShortestFirstMakesAMinimumSpanningForestOfTheFreePairs) {
  auto w = makeWorld(closedWall(0.01) + "planners:\n" + kPlanners);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0, 1);
  Roadmap roadmap;
  while (roadmap.numNodes() < 50) {
    const Eigen::Vector2d q(unit(rng), unit(rng));
    if (w->checker.isValid(q)) roadmap.addNode(q);
  }
  const int n = roadmap.numNodes();
  const NearestNeighbors nn(roadmap.nodes(), w->space.metricScale());
  Roadmap forest = roadmap;
  ASSERT_TRUE(connectShortestFirst(forest, nn, w->context, n));

  std::vector<std::vector<double>> free(n, std::vector<double>(n, -1));  // length, or -1 when blocked
  UnionFind all(n);
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j)
      if (w->validator.isValid(roadmap.node(i), roadmap.node(j))) {
        free[i][j] = free[j][i] = w->space.distance(roadmap.node(i), roadmap.node(j));
        all.unite(i, j);
      }
  // Prim's algorithm in each component of the free pairs.
  double prim = 0;
  std::vector<char> in(n, 0);
  for (int root = 0; root < n; ++root) {
    if (in[root]) continue;
    std::vector<double> best(n, std::numeric_limits<double>::infinity());
    best[root] = 0;
    for (;;) {
      int u = -1;
      for (int v = 0; v < n; ++v)
        if (!in[v] && std::isfinite(best[v]) && (u < 0 || best[v] < best[u])) u = v;
      if (u < 0) break;
      in[u] = 1;
      prim += best[u];
      for (int v = 0; v < n; ++v)
        if (!in[v] && free[u][v] >= 0) best[v] = std::min(best[v], free[u][v]);
    }
  }
  double total = 0;
  int components = 0;
  for (int i = 0; i < n; ++i) {
    components += all.find(i) == i;
    for (const Edge& e : forest.neighbours(i)) {
      if (e.to < i) continue;
      EXPECT_GE(free[i][e.to], 0) << "edge " << i << "-" << e.to << " is blocked";
      total += e.cost;
    }
    for (int j = 0; j < n; ++j) EXPECT_EQ(forest.connected(i, j), all.same(i, j)) << i << ", " << j;
  }
  ASSERT_GT(components, 1) << "the wall splits the free pairs";
  EXPECT_EQ(forest.numEdges(), n - components);
  EXPECT_NEAR(total, prim, 1e-9);
}

// fastron_panda's random queries (svmp-plan --queries 100, seed 1) on one roadmap: every query is
// solved and proven, the hard ones by repair rounds whose trees run when the components are joined
// only through an edge the proof refuses.
TEST(RoadmapQuery, SvmpAnswersFastronPandasRandomQueriesAllProven) {
  auto w = makeWorld(test::readScenario("fastron_panda.yaml"));
  w->certify();
  auto svmp = w->planner("svmp");
  ASSERT_TRUE(svmp->build(1).solved());
  for (const cspace::Query& q : experiments::randomQueries(w->scenario, 100, 1)) {
    const PlanResult r = svmp->query(q, 1);
    ASSERT_TRUE(r.solved()) << r.message;
    EXPECT_TRUE(r.certified);
    EXPECT_TRUE(test::pathIsValid(*w, r.path, q)) << "an independent dense re-check";
    // A roadmap edge is proven once, in the direction a query first used it: the proof is sound either
    // way, though bisection from the other end may stop short of it.
    for (size_t i = 0; i + 1 < r.path.size(); ++i)
      EXPECT_TRUE(w->certifier.isValid(r.path[i], r.path[i + 1]) || w->certifier.isValid(r.path[i + 1], r.path[i]))
          << "segment " << i;
  }
}

// The milestones of an SVMP roadmap as sorted coordinate lists, to compare roadmaps as sets.
std::vector<std::vector<double>> milestoneSet(const SvmpPlanner& svmp) {
  std::vector<std::vector<double>> set;
  for (const auto& q : svmp.roadmap().nodes()) set.emplace_back(q.data(), q.data() + q.size());
  std::sort(set.begin(), set.end());
  return set;
}

// With lazy edges the build's descent ends that collide are centred only when a query first fails
// on the lazy roadmap: the build holds the free ends, and after that query the roadmap holds the same
// milestones as a build that centres at once (defer_centring: false), the same seed.
TEST(RoadmapQuery, SvmpCentresCollidingDescentEndsWhenAQueryFirstNeedsThem) {
  // No trees: a query they answer keeps their nodes too.
  auto deferred_world = makeWorld(gapScenario(0.002, "  svmp: {repair_rounds: 0, lazy_trees: 0}\n"));
  auto eager_world = makeWorld(gapScenario(0.002, "  svmp: {repair_rounds: 0, lazy_trees: 0, defer_centring: false}\n"));
  auto deferred = deferred_world->planner("svmp"), eager = eager_world->planner("svmp");
  ASSERT_TRUE(deferred->build(1).solved());
  ASSERT_TRUE(eager->build(1).solved());
  const auto& d = dynamic_cast<const SvmpPlanner&>(*deferred);
  const auto& e = dynamic_cast<const SvmpPlanner&>(*eager);
  const auto built = milestoneSet(d), all = milestoneSet(e);
  ASSERT_LT(built.size() + 5, all.size()) << "the gap's walls leave colliding descent ends to centre";
  EXPECT_TRUE(std::includes(all.begin(), all.end(), built.begin(), built.end()));
  deferred->query(deferred_world->query(), 1);
  EXPECT_EQ(milestoneSet(d), all);
}

// Trees before the eager pass (SvmpOptions::lazy_trees), on Fig 4.4's seeds whose lazy roadmap does not
// answer: the trees join the start's and the goal's components, so no eager pass ran (without the
// trees it did), with fewer checks, and the path is certified and free when re-checked at a quarter of
// the resolution. After an eager pass the lazy edges it dropped come back only within the components
// it proved: each unchecked edge joins two nodes that checked edges join.
TEST(RoadmapQuery, SvmpTreesJoinWhatTheLazyRoadmapDoesNotBeforeAnEagerPass) {
  auto w = makeWorld(test::readScenario("thesis_fig4_4.yaml"));
  w->certify();
  cspace::ParameterSet without_trees = w->scenario.paramsFor("svmp");
  without_trees.set("lazy_trees", "0");
  int joined = 0;
  for (std::uint64_t seed : {1, 9, 10}) {
    auto with = w->planner("svmp");
    auto without = makePlanner("svmp", w->context, without_trees);
    const PlanResult a = with->solve(w->query(), seed), b = without->solve(w->query(), seed);
    ASSERT_TRUE(a.solved() && b.solved()) << "seed " << seed;
    EXPECT_TRUE(a.certified);
    const auto& eager = dynamic_cast<const SvmpPlanner&>(*without);
    EXPECT_TRUE(eager.eagerPassRun());
    Roadmap proven = eager.roadmap();
    std::vector<std::pair<int, int>> restored;
    for (const auto& [a, e] : proven.dropUnchecked()) restored.emplace_back(a, e.to);
    EXPECT_FALSE(restored.empty()) << "seed " << seed;
    for (const auto& [a, b] : restored) EXPECT_TRUE(proven.connected(a, b)) << a << "-" << b;
    if (dynamic_cast<const SvmpPlanner&>(*with).eagerPassRun()) continue;
    ++joined;
    EXPECT_LT(a.collision_checks, b.collision_checks) << "seed " << seed;
    expectFreeAtQuarterResolution(*w, a.path, "seed " + std::to_string(seed));
  }
  EXPECT_GE(joined, 2);
}

// Cheaper repairs first: on Fig 4.4's seeds whose lazy roadmap does not answer, trees of half the
// size come before the build's deferred centring: on several seeds they answer with the centring
// still pending (with centring first it was spent on seeds the trees then answered), certified and
// free when re-checked finely.
TEST(RoadmapQuery, SvmpTriesSmallTreesBeforeTheDeferredCentring) {
  auto w = makeWorld(test::readScenario("thesis_fig4_4.yaml"));
  w->certify();
  int before_centring = 0;
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    auto planner = w->planner("svmp");
    const auto& svmp = dynamic_cast<const SvmpPlanner&>(*planner);
    ASSERT_TRUE(planner->build(seed).solved());
    const int pending = svmp.pendingCentring();
    ASSERT_GT(pending, 0) << "seed " << seed << ": Fig 4.4's descent ends that collide wait for a query";
    const PlanResult r = planner->query(w->query(), seed);
    ASSERT_TRUE(r.solved()) << r.message;
    if (svmp.treeAnswers() != 1 || svmp.pendingCentring() != pending) continue;
    ++before_centring;
    EXPECT_FALSE(svmp.eagerPassRun()) << "seed " << seed;
    EXPECT_TRUE(r.certified);
    expectFreeAtQuarterResolution(*w, r.path, "seed " + std::to_string(seed));
  }
  EXPECT_GE(before_centring, 2);
}

// panda_shelf's planner with 400 samples a tree (the file's count until the twenty-third session),
// whose roadmap the next two tests' seeds were chosen on.
std::unique_ptr<Planner> pandaShelfSvmp400(const test::World& w) {
  cspace::ParameterSet params = w.scenario.paramsFor("svmp");
  params.set("samples_per_tree", "400");
  return makePlanner("svmp", w.context, params);
}

// Random queries on one roadmap (panda_shelf, as svmp-plan --queries 60 --seed 2): every query the
// roadmap does not answer tries the trees before any repair round, not only the build's first. More
// than one query is answered by trees, certified and free when re-checked finely; the trees' nodes
// join the roadmap, so the same query asked again is answered by the roadmap (no trees, no repair).
TEST(RoadmapQuery, SvmpTriesTreesAtEveryQueryTheRoadmapDoesNotAnswerAndKeepsTheirNodes) {
  auto w = makeWorld(test::readScenario("panda_shelf.yaml"));
  w->certify();
  auto planner = pandaShelfSvmp400(*w);
  const auto& svmp = dynamic_cast<const SvmpPlanner&>(*planner);
  ASSERT_TRUE(planner->build(2).solved());
  int by_trees = 0;
  for (const cspace::Query& q : experiments::randomQueries(w->scenario, 60, 2)) {
    const int answers = svmp.treeAnswers();
    const PlanResult r = planner->query(q, 2);
    ASSERT_TRUE(r.solved()) << r.message;
    if (svmp.treeAnswers() == answers) continue;
    ++by_trees;
    EXPECT_TRUE(r.certified);
    expectFreeAtQuarterResolution(*w, r.path, "tree answer " + std::to_string(by_trees));
    const int nodes = svmp.roadmap().numNodes();
    const PlanResult again = planner->query(q, 2);
    ASSERT_TRUE(again.solved()) << again.message;
    EXPECT_EQ(svmp.treeAnswers(), answers + 1) << "tree answer " << by_trees;
    EXPECT_EQ(svmp.roadmap().numNodes(), nodes);
    EXPECT_TRUE(again.certified);
  }
  EXPECT_GE(by_trees, 2);
}

// Trees that join the start's and the goal's components where the path between them crosses a lazy
// edge that is blocked grow on from the components left (panda_shelf, 400 samples a tree, as
// svmp-plan --queries 100 --seed 1): the first query the lazy roadmap does not answer (its 6th) is
// answered by trees, certified and free when re-checked finely, with the build's centring still
// pending and no eager pass. Trees that stopped at their first join left it to the centring and the
// eager pass (22.9k checks, against RRTConnect's 1.5k).
TEST(RoadmapQuery, SvmpTreesGrowOnWhenTheirJoinCrossesABlockedLazyEdge) {
  auto w = makeWorld(test::readScenario("panda_shelf.yaml"));
  w->certify();
  auto planner = pandaShelfSvmp400(*w);
  const auto& svmp = dynamic_cast<const SvmpPlanner&>(*planner);
  ASSERT_TRUE(planner->build(1).solved());
  const int pending = svmp.pendingCentring();
  ASSERT_GT(pending, 0);
  const std::vector<cspace::Query> queries = experiments::randomQueries(w->scenario, 6, 1);
  for (const cspace::Query& q : queries) {
    const PlanResult r = planner->query(q, 1);
    ASSERT_TRUE(r.solved()) << r.message;
    EXPECT_TRUE(r.certified);
    expectFreeAtQuarterResolution(*w, r.path, "query");
  }
  EXPECT_EQ(svmp.treeAnswers(), 1);
  EXPECT_EQ(svmp.pendingCentring(), pending);
  EXPECT_FALSE(svmp.eagerPassRun());
}

// Before a repaired query fails, larger trees get one last try: Fig 4.6 with a roadmap, trees and
// repair too small to join its start and goal (5 samples per obstacle, trees of 10 samples, one
// repair round of 2 samples) is answered by them, after the eager pass, certified and free when
// re-checked finely.
TEST(RoadmapQuery, SvmpTriesLargerTreesBeforeARepairedQueryFails) {
  auto w = makeWorld(test::readScenario("thesis_fig4_6.yaml"));
  w->certify();
  cspace::ParameterSet small = w->scenario.paramsFor("svmp");
  for (const auto& [key, value] : {std::pair{"samples_per_tree", "5"}, {"lazy_trees", "10"}, {"repair_rounds", "1"},
                                   {"repair_samples", "2"}})
    small.set(key, value);
  int last_trees = 0;
  for (std::uint64_t seed : {3, 11, 15}) {
    auto planner = makePlanner("svmp", w->context, small);
    const auto& svmp = dynamic_cast<const SvmpPlanner&>(*planner);
    const PlanResult r = planner->solve(w->query(), seed);
    if (!r.solved() || !svmp.eagerPassRun() || svmp.treeAnswers() != 1) continue;
    ++last_trees;
    EXPECT_TRUE(r.certified);
    expectFreeAtQuarterResolution(*w, r.path, "seed " + std::to_string(seed));
  }
  EXPECT_GE(last_trees, 2);
}

// A pair that no path joins (closedWall): the query fails after its
// repair rounds, and the roadmap is the one it found, with the build's centred descent ends (above).
// Those rounds' nodes filled both components; kept, they would slow every later query and make the
// next such pair dearer.
TEST(RoadmapQuery, SvmpFailedQueryLeavesTheRoadmapAsItFoundIt) {
  const std::string world = closedWall(0.002);
  auto w = makeWorld(world);
  w->certify();
  auto planner = w->planner("svmp");
  const auto& svmp = dynamic_cast<const SvmpPlanner&>(*planner);
  ASSERT_TRUE(planner->build(1).solved());
  auto centred_world = makeWorld(world + "planners:\n  svmp: {defer_centring: false}\n");
  auto centred = centred_world->planner("svmp");
  ASSERT_TRUE(centred->build(1).solved());
  const int nodes = dynamic_cast<const SvmpPlanner&>(*centred).roadmap().numNodes();
  const PlanResult r = planner->query(w->query(), 1);
  ASSERT_FALSE(r.solved());
  std::smatch m;
  const std::string message = r.message;
  ASSERT_TRUE(std::regex_search(message, m, std::regex("of ([0-9]+) nodes"))) << message;
  EXPECT_GT(std::stoi(m[1]), nodes + 100) << "the repair rounds added nodes: " << message;
  EXPECT_NE(message.find("; trees of 3000 to 24000 uniform samples did not join them)"), std::string::npos) << message;
  EXPECT_EQ(svmp.roadmap().numNodes(), nodes);
  EXPECT_EQ(r.milestones, nodes);
}

// A query under a time limit that has fired reports `timeout`, not a disconnection its cut-short
// checks cannot prove, and leaves the built roadmap as it was (svmp's repairs and eager pass would
// otherwise change it for later queries).
TEST(RoadmapQuery, AQueryPastItsTimeLimitIsATimeoutAndKeepsTheRoadmap) {
  auto w = makeWorld(gapScenario(0.03, kPlanners));
  w->certify();
  for (const char* name : {"svmp", "prm"}) {
    auto planner = w->planner(name);
    ASSERT_TRUE(planner->build(1).solved()) << name;
    const Roadmap before = *planner->view().roadmap;
    const PlanResult r = planner->query(w->query(), 1, Termination::when([] { return true; }));
    EXPECT_EQ(r.status, PlanStatus::kTimeout) << name << ": " << r.message;
    EXPECT_EQ(planner->view().roadmap->numNodes(), before.numNodes()) << name;
    EXPECT_EQ(planner->view().roadmap->numEdges(), before.numEdges()) << name;
    // The next query answers as on a roadmap no limit touched.
    auto fresh = w->planner(name);
    ASSERT_TRUE(fresh->build(1).solved());
    const PlanResult expected = fresh->query(w->query(), 1), next = planner->query(w->query(), 1);
    EXPECT_EQ(next.status, expected.status) << name;
    EXPECT_EQ(next.path, expected.path) << name;
  }
}

// svmp.trees_before_build: a single query whose straight motion is blocked grows trees first and,
// where they join, answers with no obstacle sampled; where they do not (a gap narrower than their
// steps, in one sample), the build answers as before.
TEST(RoadmapQuery, SvmpTreesBeforeTheBuildAnswerWithoutLearning) {
  const auto around_the_block = [](int trees) {
    return "robot: {type: point, bounds: {lower: [0, 0], upper: [1, 1]}}\n"
           "obstacles:\n  - {name: block, shape: box, size: [0.2, 0.2, 1], position: [0.5, 0.5, 0]}\n"
           "start: [0.1, 0.5]\ngoal: [0.9, 0.5]\nresolution: 0.01\n"
           "planners:\n  svmp: {trees_before_build: " + std::to_string(trees) + "}\n";
  };
  auto w = makeWorld(around_the_block(500));
  w->certify();
  auto planner = w->planner("svmp");
  const PlanResult r = planner->solve(w->query(), 1);
  ASSERT_TRUE(r.solved()) << r.message;
  EXPECT_TRUE(r.certified);
  EXPECT_GT(r.path.size(), 2u);
  EXPECT_TRUE(test::pathIsValid(*w, r.path));
  EXPECT_EQ(r.support_vectors, 0u);
  EXPECT_GE(r.milestones, r.path.size());  // the trees' nodes, the path's among them
  EXPECT_GE(r.roadmap_edges + 1, r.milestones - 1);  // two trees of k nodes hold k - 2 edges, then the join
  EXPECT_FALSE(planner->built());
  auto build_first = makeWorld(around_the_block(0));
  const PlanResult learned = build_first->planner("svmp")->solve(build_first->query(), 1);
  ASSERT_TRUE(learned.solved()) << learned.message;
  EXPECT_GT(learned.support_vectors, 0u);

  auto gap = makeWorld(gapScenario(
      0.03, "  svmp: {sigma: 0.06, C: 100, step: 0.05, samples_per_tree: 200, k: 10, trees_before_build: 1}\n"));
  gap->certify();
  auto through_gap = gap->planner("svmp");
  const PlanResult fallback = through_gap->solve(gap->query(), 4);
  ASSERT_TRUE(fallback.solved()) << fallback.message;
  EXPECT_GT(fallback.support_vectors, 0u);
  EXPECT_TRUE(through_gap->built());
  EXPECT_TRUE(test::pathIsValid(*gap, fallback.path));

  // A time limit that ends the trees ends the run, saying so, with no build: a wall across the space.
  auto endless = makeWorld(
      "robot: {type: point, bounds: {lower: [0, 0], upper: [1, 1]}}\n"
      "obstacles:\n  - {name: wall, shape: box, size: [0.2, 1.2, 1], position: [0.5, 0.5, 0]}\n"
      "start: [0.1, 0.5]\ngoal: [0.9, 0.5]\nresolution: 0.01\n"
      "planners:\n  svmp: {trees_before_build: 1000000}\n");
  auto stopped = endless->planner("svmp");
  int polls = 0;
  const PlanResult timeout = stopped->solve(endless->query(), 1, Termination::when([&] { return ++polls > 200; }));
  EXPECT_EQ(timeout.status, PlanStatus::kTimeout);
  EXPECT_NE(timeout.message.find("growing trees before the build"), std::string::npos) << timeout.message;
  EXPECT_GT(timeout.milestones, 2u);
  EXPECT_EQ(timeout.support_vectors, 0u);
  EXPECT_FALSE(stopped->built());
}

}  // namespace
}  // namespace svmp::planners
