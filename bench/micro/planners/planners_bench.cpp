// Hot paths of the planners: obstacle sampling (thesis Algorithm 1), the colouring of obstacle classes,
// milestone descent on the risk
// function (truncated vs full evaluation, thesis ch. 4.3.1), k-nearest neighbours in the weighted metric
// (a fixed set, and one growing as a repair grows it), one query on a built SVMP roadmap (many queries, `svmp-plan --queries`), a lazy query's repeated
// searches, and the eager pass that connects a roadmap's milestones (node order, as the thesis, or
// shortest pairs first), and whole single queries of SVMP and PRM beside OMPL's planners (BM_Solve).
// The world is thesis Fig 3.7 (bench/scenarios/thesis_fig3_7.yaml) or the 5-DoF arm of Fig 4.4; the
// queries run on svpp_3d20_01 (a point among 20 boxes) and fastron_panda (the Panda).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <map>
#include <memory>
#include <optional>
#include <random>
#include <set>

#include "cspace/certified_motion_validator.hpp"
#include "cspace/collision_checker.hpp"
#include "planners/class_colouring.hpp"
#include "planners/exact_setup.hpp"
#include "planners/obstacle_sampler.hpp"
#include "planners/planner_registry.hpp"
#include "cspace/scenario/scenario.hpp"
#include "bench/experiments/experiment.hpp"
#include "planners/nearest_neighbors.hpp"
#include "planners/roadmap_builder.hpp"
#include "planners/svmp_planner.hpp"
#include "svm/local_one_vs_rest.hpp"

namespace svmp {
namespace {

struct World {
  cspace::Scenario scenario;
  cspace::ConfigurationSpace space;
  cspace::CollisionChecker checker;
  cspace::DiscreteMotionValidator validator;
  planners::PlanningContext context;
  std::unique_ptr<planners::SvmpPlanner> svmp;

  World(const std::string& file, double sigma, double step, int per_tree, bool truncated)
      : scenario(cspace::loadScenario(std::string(SVMP_SOURCE_DIR) + "/bench/scenarios/" + file)),
        space(scenario.makeSpace()),
        checker(scenario.robot, scenario.environment, scenario.self_collision),
        validator(checker, space, scenario.resolution),
        context{space, checker, validator, 1} {
    planners::SvmpOptions o;
    o.sigma = sigma;
    o.step = step;
    o.samples_per_tree = per_tree;
    o.truncated = truncated;
    svmp = std::make_unique<planners::SvmpPlanner>(context, o);
    planners::PhaseTimes times;
    svmp->sampleObstacle(1, times);
    svmp->trainMultiSvm(times);
  }
};

World& world(int which, bool truncated) {
  static World fig3_7_t("thesis_fig3_7.yaml", 0.5, 0.3, 300, true);
  static World fig3_7_f("thesis_fig3_7.yaml", 0.5, 0.3, 300, false);
  static World fig4_4_t("thesis_fig4_4.yaml", 0.3, 0.15, 300, true);
  static World fig4_4_f("thesis_fig4_4.yaml", 0.3, 0.15, 300, false);
  if (which == 0) return truncated ? fig3_7_t : fig3_7_f;
  return truncated ? fig4_4_t : fig4_4_f;
}

// One milestone descent per iteration, from the boundary samples in turn.
void BM_MilestoneDescent(benchmark::State& state) {
  World& w = world(static_cast<int>(state.range(0)), state.range(1) != 0);
  const auto& samples = w.svmp->samples();
  std::vector<int> boundary;
  for (int i = 0; i < samples.size(); ++i)
    if (samples.boundary[i]) boundary.push_back(i);
  const planners::DescentOptions options = w.svmp->options().descent();
  size_t next = 0;
  long steps = 0, exact = 0;
  for (auto _ : state) {
    const int i = boundary[next++ % boundary.size()];
    const int k = w.svmp->risk()->classIndex(samples.labels[i]);
    const planners::DescentResult r = w.svmp->risk()->descend(k, samples.points.col(i), w.space, options);
    steps += r.iterations;
    exact += r.exact;
    benchmark::DoNotOptimize(r);
  }
  state.SetItemsProcessed(state.iterations());
  // The workload: descents differ in length with the samples, and steps in cost with the models.
  state.counters["steps_per_descent"] = static_cast<double>(steps) / static_cast<double>(state.iterations());
  state.counters["exact_share"] = static_cast<double>(exact) / static_cast<double>(state.iterations());
  state.counters["support_vectors"] = w.svmp->supportVectors();
  state.counters["boundary_samples"] = static_cast<double>(boundary.size());
  state.SetLabel(std::string(state.range(0) == 0 ? "fig3_7" : "fig4_4") +
                 (state.range(1) ? " truncated" : " full"));
}
BENCHMARK(BM_MilestoneDescent)->ArgsProduct({{0, 1}, {1, 0}});

void BM_ObstacleSampling(benchmark::State& state) {
  World& w = world(static_cast<int>(state.range(0)), true);
  planners::ObstacleSamplerOptions o;
  o.step = state.range(0) == 0 ? 0.3 : 0.15;
  o.samples_per_tree = 300;
  std::uint64_t seed = 1;
  for (auto _ : state) benchmark::DoNotOptimize(planners::sampleObstacles(w.checker, w.space, o, seed++, 1));
  state.SetLabel(state.range(0) == 0 ? "fig3_7" : "fig4_4");
}
BENCHMARK(BM_ObstacleSampling)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

void BM_NearestNeighbors(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0)), dim = 6;
  cspace::Rng rng(3);
  std::vector<Eigen::VectorXd> points(n);
  std::uniform_real_distribution<double> u(-3, 3);
  for (auto& p : points) {
    p.resize(dim);
    for (int d = 0; d < dim; ++d) p[d] = u(rng);
  }
  const planners::NearestNeighbors nn(points, Eigen::VectorXd::LinSpaced(dim, 2.0, 0.5));
  size_t next = 0;
  for (auto _ : state) benchmark::DoNotOptimize(nn.nearest(points[next++ % n], 31));
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_NearestNeighbors)->Arg(1000)->Arg(10000);

// A roadmap index growing as SVMP's repair grows it: 10,000 points in 6 dimensions, then 50 rounds
// that add 200 points each and ask the 10 nearest of every new one. Arg 0: a tree built again
// after each round (before 4397b46); 1: NearestNeighbors::extend.
void BM_NearestNeighborsGrowing(benchmark::State& state) {
  const int dim = 6, start = 10000, rounds = 50, per_round = 200;
  cspace::Rng rng(5);
  std::uniform_real_distribution<double> u(-3, 3);
  std::vector<Eigen::VectorXd> all(start + rounds * per_round, Eigen::VectorXd(dim));
  for (auto& p : all)
    for (int d = 0; d < dim; ++d) p[d] = u(rng);
  const Eigen::VectorXd scale = Eigen::VectorXd::LinSpaced(dim, 2.0, 0.5);
  for (auto _ : state) {
    std::vector<Eigen::VectorXd> points(all.begin(), all.begin() + start);
    std::optional<planners::NearestNeighbors> nn(std::in_place, points, scale);
    for (int r = 0; r < rounds; ++r) {
      const size_t first = points.size();
      points.insert(points.end(), all.begin() + static_cast<long>(first), all.begin() + static_cast<long>(first) + per_round);
      if (state.range(0) == 1)
        nn->extend(points);
      else
        nn.emplace(points, scale);
      for (size_t i = first; i < points.size(); ++i) benchmark::DoNotOptimize(nn->nearest(points[i], 10));
    }
  }
  state.SetItemsProcessed(state.iterations() * rounds);
}
BENCHMARK(BM_NearestNeighborsGrowing)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

// A scenario file of bench/scenarios and SVMP on it with the file's parameters, built with seed 1
// (`built` false when the build failed); paths proven when `certify`.
struct BuiltSvmp {
  cspace::Scenario scenario;
  cspace::ConfigurationSpace space;
  cspace::CollisionChecker checker;
  cspace::DiscreteMotionValidator validator;
  cspace::CertifiedMotionValidator certifier;
  planners::PlanningContext context;
  planners::SvmpPlanner svmp;
  bool built;

  BuiltSvmp(const std::string& file, bool certify)
      : scenario(cspace::loadScenario(std::string(SVMP_SOURCE_DIR) + "/bench/scenarios/" + file)),
        space(scenario.makeSpace()),
        checker(scenario.robot, scenario.environment, scenario.self_collision),
        validator(checker, space, scenario.resolution),
        certifier(checker, space, scenario.resolution),
        context{space, checker, validator, 1, certify ? &certifier : nullptr},
        svmp(context, planners::SvmpOptions::fromParameters(scenario.paramsFor("svmp"))),
        built(svmp.build(1).solved()) {}
};

// The per-class neighbourhoods SVMP trains each obstacle's model on (svm::classNeighbourhoods) over
// the boundary samples of Fig 4.10 (arg 0) and panda_shelf (arg 1), built with the files' parameters
// (seed 1) and scaled by the metric, as SvmpPlanner::trainMultiSvm gives them (it adds a tenth of the
// interior samples).
void BM_ClassNeighbourhoods(benchmark::State& state) {
  static BuiltSvmp fig4_10("thesis_fig4_10.yaml", false), shelf("panda_shelf.yaml", false);
  BuiltSvmp& w = state.range(0) == 0 ? fig4_10 : shelf;
  const planners::ObstacleSamples& samples = w.svmp.samples();
  std::vector<int> kept, labels;
  for (int i = 0; i < samples.size(); ++i)
    if (samples.boundary[i]) kept.push_back(i), labels.push_back(samples.labels[i]);
  Eigen::MatrixXd scaled(w.space.dim(), static_cast<Eigen::Index>(kept.size()));
  for (size_t j = 0; j < kept.size(); ++j)
    scaled.col(static_cast<Eigen::Index>(j)) = samples.points.col(kept[j]).cwiseProduct(w.space.metricScale());
  const std::set<int> ids(labels.begin(), labels.end());
  const std::vector<int> classes(ids.begin(), ids.end());
  const svm::Kernel kernel = svm::Kernel::rbfFromSigma(w.svmp.options().sigma);
  std::vector<std::vector<int>> hoods;
  for (auto _ : state) hoods = svm::classNeighbourhoods(scaled, labels, classes, kernel);
  state.counters["samples"] = static_cast<double>(kept.size());
  state.counters["share"] = svm::neighbourhoodShare(hoods, scaled.cols());
  state.SetLabel(state.range(0) == 0 ? "fig4_10" : "panda_shelf");
}
BENCHMARK(BM_ClassNeighbourhoods)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

// The colouring of obstacle classes (planners/class_colouring.hpp) over forest_200's samples (200
// boxes, a point robot), as SvmpPlanner::trainMultiSvm calls it (adjacent within 3 sigma), built with
// the file's parameters (seed 1).
void BM_ObstacleColouring(benchmark::State& state) {
  static BuiltSvmp forest("forest_200.yaml", false);
  const planners::ObstacleSamples& samples = forest.svmp.samples();
  std::map<int, int> colours;
  for (auto _ : state)
    colours = planners::colourClasses(samples.points, samples.labels, forest.space.metricScale(),
                                      3 * forest.svmp.options().sigma);
  int most = 0;
  for (const auto& [label, c] : colours) most = std::max(most, c);
  state.counters["samples"] = samples.size();
  state.counters["colours"] = most;
}
BENCHMARK(BM_ObstacleColouring)->Unit(benchmark::kMicrosecond);

// One query per iteration on SVMP's roadmap built with the file's parameters (seed 1): the roadmap is
// assigned to a reused copy, as SvmpPlanner::answer does, and queryRoadmap answers in turn the 100
// valid start-goal pairs of `svmp-plan --queries 100 --seed 1`, every path proven (no repair: the
// roadmap stays the same).
void BM_RoadmapQuery(benchmark::State& state) {
  const std::string file = state.range(0) == 0 ? "svpp_3d20_01.yaml" : "fastron_panda.yaml";
  BuiltSvmp world(file, true);
  if (!world.built) {
    state.SkipWithError("svmp build failed");
    return;
  }
  const cspace::Scenario& scenario = world.scenario;
  const cspace::ConfigurationSpace& space = world.space;
  const planners::PlanningContext& context = world.context;
  const planners::SvmpPlanner& svmp = world.svmp;
  const planners::Roadmap& roadmap = svmp.roadmap();
  const planners::NearestNeighbors nn(roadmap.nodes(), space.metricScale());
  const std::vector<cspace::Query> queries = experiments::randomQueries(scenario, 100, 1);
  planners::Roadmap with_query;
  size_t next = 0;
  long solved = 0, straight = 0;
  for (auto _ : state) {
    with_query = roadmap;
    const planners::QueryOutcome out = queryRoadmap(with_query, nn, context, queries[next++ % queries.size()],
                                                    svmp.options().k);
    solved += !out.path.empty();
    straight += out.path.size() == 2;
    benchmark::DoNotOptimize(out);
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["solved_share"] = static_cast<double>(solved) / static_cast<double>(state.iterations());
  state.counters["straight_share"] = static_cast<double>(straight) / static_cast<double>(state.iterations());
  state.counters["milestones"] = roadmap.numNodes();
  state.SetLabel(file.substr(0, file.size() - 5));
}
BENCHMARK(BM_RoadmapQuery)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

// A lazy query's repeated searches (provenPath's loop, its motion checks replaced by a table made
// before timing): 300 milestones uniform in the free part of the unit square among 200 discs of radius
// 0.02 (forest_200 scaled to the unit square), each joined unchecked to its 10 nearest. Search corner
// to corner, remove the path's edges that cross a disc, search again until a path is free.
void BM_LazySearch(benchmark::State& state) {
  cspace::Rng rng(5);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Eigen::Vector2d> discs(200);
  for (auto& c : discs) c = {u(rng), u(rng)};
  const auto crosses = [&](const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
    for (const auto& c : discs) {
      const Eigen::Vector2d ab = b - a;
      const double t = ab.squaredNorm() > 0 ? std::clamp((c - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0.0;
      if ((a + t * ab - c).norm() < 0.02) return true;
    }
    return false;
  };
  planners::Roadmap roadmap;
  for (const Eigen::Vector2d& corner : {Eigen::Vector2d(0.01, 0.01), Eigen::Vector2d(0.99, 0.99)})
    roadmap.addNode(corner);
  while (roadmap.numNodes() < 300) {
    const Eigen::Vector2d q(u(rng), u(rng));
    if (!crosses(q, q)) roadmap.addNode(q);
  }
  const planners::NearestNeighbors nn(roadmap.nodes(), Eigen::Vector2d::Ones());
  std::set<std::pair<int, int>> blocked;  // edges (i < j) that cross a disc
  for (int i = 0; i < roadmap.numNodes(); ++i)
    for (int j : nn.nearest(roadmap.node(i), 11))
      if (j > i && !roadmap.hasEdge(i, j)) {
        roadmap.addEdge(i, j, (roadmap.node(i) - roadmap.node(j)).norm(), false);
        if (crosses(roadmap.node(i), roadmap.node(j))) blocked.insert({i, j});
      }
  const auto metric = [&](int v) { return (roadmap.node(v) - roadmap.node(1)).norm(); };
  planners::Roadmap lazy;
  long searches = 0;
  for (auto _ : state) {
    lazy = roadmap;
    for (bool free = false; !free;) {
      const auto path = lazy.shortestPath(0, 1, metric);
      ++searches;
      free = true;
      for (size_t i = 0; i + 1 < path.size(); ++i)
        if (blocked.count(std::minmax(path[i], path[i + 1]))) lazy.removeEdge(path[i], path[i + 1]), free = false;
    }
  }
  state.counters["searches"] = static_cast<double>(searches) / static_cast<double>(state.iterations());
}
BENCHMARK(BM_LazySearch)->Unit(benchmark::kMicrosecond);

// The eager pass over Fig 4.4's SVMP milestones (the file's parameters, seed 1, after its first query
// centred the deferred ones): the thesis' MakeRoadmap in node order (connectMilestones, arg 0) or
// shortest pairs first (connectShortestFirst, arg 1, what SVMP runs after a failed lazy query), on a
// copy of the nodes without edges each iteration.
void BM_EagerPass(benchmark::State& state) {
  BuiltSvmp world("thesis_fig4_4.yaml", false);
  if (!world.built) {
    state.SkipWithError("svmp build failed");
    return;
  }
  planners::SvmpPlanner& svmp = world.svmp;
  const cspace::ConfigurationSpace& space = world.space;
  const cspace::DiscreteMotionValidator& validator = world.validator;
  const planners::PlanningContext& context = world.context;
  svmp.query(world.scenario.queries.front(), 1);
  planners::Roadmap nodes;
  for (const auto& q : svmp.roadmap().nodes()) nodes.addNode(q);
  const planners::NearestNeighbors nn(nodes.nodes(), space.metricScale());
  const int k = svmp.options().k;
  const bool shortest_first = state.range(0) == 1;
  planners::Roadmap roadmap;
  const std::uint64_t calls_before = validator.calls();
  for (auto _ : state) {
    roadmap = nodes;
    shortest_first ? planners::connectShortestFirst(roadmap, nn, context, k)
                   : planners::connectMilestones(roadmap, nn, context, k);
    benchmark::DoNotOptimize(roadmap);
  }
  state.counters["motions"] = static_cast<double>(validator.calls() - calls_before) / static_cast<double>(state.iterations());
  state.counters["edges"] = roadmap.numEdges();
  state.counters["milestones"] = nodes.numNodes();
  state.SetLabel(shortest_first ? "shortest first" : "node order");
}
BENCHMARK(BM_EagerPass)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

// Whole single queries as svmp-plan runs them (the exact setup: FCL checker, sampled validator,
// certifier, repairer; the file's parameters), our planners beside OMPL's on the same checker, so
// that scripts/bench_ratios pairs them run by run (`--ours svmp --rival ompl-rrtconnect`). Each
// benchmark solves seeds 1-20 once: its time is the mean over svmp-plan's 20 seeds, less the time
// the run spent counting (PlanResult::counting_ms), as svmp-plan reports it. solved_share counts
// certified paths.
void BM_Solve(benchmark::State& state, const char* file, const char* planner) {
  struct Setup {
    cspace::Scenario scenario;
    planners::ExactSetup exact;
    explicit Setup(const std::string& file)
        : scenario(cspace::loadScenario(std::string(SVMP_SOURCE_DIR) + "/bench/scenarios/" + file)), exact(scenario, 1) {}
  };
  static std::map<std::string, std::unique_ptr<Setup>> setups;
  auto& setup = setups[file];
  if (!setup) setup = std::make_unique<Setup>(file);
  std::unique_ptr<planners::Planner> p;
  try {
    p = planners::makePlanner(planner, setup->exact.planning, setup->scenario.paramsFor(planner));
  } catch (const std::exception& e) {  // OMPL's planners in a build without OMPL
    state.SkipWithError(e.what());
    return;
  }
  std::uint64_t seed = 0;
  double solved = 0, checks = 0;
  for (auto _ : state) {
    const auto t0 = planners::Clock::now();
    const planners::PlanResult r =
        p->solve(setup->scenario.queries.front(), 1 + seed++ % 20, planners::Termination::after(60));
    state.SetIterationTime((planners::msSince(t0) - r.counting_ms) / 1e3);
    solved += r.solved();
    checks += static_cast<double>(r.collision_checks);
  }
  state.counters["solved_share"] = solved / static_cast<double>(state.iterations());
  state.counters["checks"] = checks / static_cast<double>(state.iterations());
}
#define SVMP_BM_SOLVE(file, planner)                                                    \
  BENCHMARK_CAPTURE(BM_Solve, planner/file, #file ".yaml", #planner)->Iterations(20)    \
      ->UseManualTime()->Unit(benchmark::kMillisecond)
SVMP_BM_SOLVE(thesis_fig4_4, svmp);
SVMP_BM_SOLVE(thesis_fig4_4, prm);
SVMP_BM_SOLVE(thesis_fig4_4, ompl-rrtconnect);
SVMP_BM_SOLVE(thesis_fig4_4, ompl-prm);
SVMP_BM_SOLVE(forest_200, svmp);
SVMP_BM_SOLVE(forest_200, prm);
SVMP_BM_SOLVE(forest_200, ompl-rrtconnect);
SVMP_BM_SOLVE(forest_200, ompl-prm);
SVMP_BM_SOLVE(thesis_fig4_6, svmp);
SVMP_BM_SOLVE(thesis_fig4_6, ompl-rrtconnect);
SVMP_BM_SOLVE(thesis_fig4_10, svmp);
SVMP_BM_SOLVE(thesis_fig4_10, ompl-rrtconnect);

}  // namespace
}  // namespace svmp

BENCHMARK_MAIN();
