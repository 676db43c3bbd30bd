#include "planners/svmp_planner.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <optional>
#include <random>
#include <set>

#include "planners/planner_registry.hpp"
#include "planners/class_colouring.hpp"
#include "planners/roadmap_builder.hpp"
#include "planners/tree_connect.hpp"
#include "svm/local_one_vs_rest.hpp"

namespace svmp::planners {

namespace {
// SvmpPlanner::obstacleTrees, before options_ is resolved (`inner`: Environment::innerObstacles).
int obstacleTrees(const PlanningContext& context, const SvmpOptions& options, const std::vector<char>& inner) {
  return context.checker.environment().numReal() - static_cast<int>(std::count(inner.begin(), inner.end(), 1)) +
         (options.sample_self_collision && context.checker.checksSelfCollision() ? 1 : 0);
}
}  // namespace

SVMP_REGISTER_PLANNER("svmp", [](const PlanningContext& context, const cspace::ParameterSet& params) {
  const SvmpOptions o = SvmpOptions::fromParameters(params);
  auto planner = std::make_unique<SvmpPlanner>(context, o);  // holds nothing yet: samples come at build
  // Every sample is an SVM training point.
  constexpr long kMaxSamples = 2000000;
  const long trees = planner->obstacleTrees();
  if (static_cast<long>(o.samples_per_tree) * trees > kMaxSamples)
    throw cspace::ScenarioError("planners.svmp.samples_per_tree: " + std::to_string(o.samples_per_tree) + " x " +
                                std::to_string(trees) + " trees exceeds " + std::to_string(kMaxSamples) +
                                " obstacle samples");
  return planner;
});

namespace {
// `classes: auto` above 8 obstacles: the per-obstacle neighbourhoods (svm/local_one_vs_rest.hpp) of
// the scaled samples when there are at most kMaxObstacleClasses and they hold under half of one full
// problem's kernel entries, else none (colours). A colouring trains at least two models on (almost)
// every sample, as its colours' neighbourhoods cover the space; sparse obstacles (3-D forests, an
// arm's clutter) train faster one per obstacle (docs/dev-log.md). Beyond kMaxObstacleClasses
// colours keep the model count bounded where obstacles are many (issue 13).
constexpr int kMaxObstacleClasses = 64;
std::vector<std::vector<int>> smallObstacleNeighbourhoods(const Eigen::MatrixXd& scaled, const std::vector<int>& labels,
                                                          const std::map<int, double>& weights, double sigma) {
  if (static_cast<int>(weights.size()) > kMaxObstacleClasses) return {};
  std::vector<int> ids;
  for (const auto& [label, w] : weights) ids.push_back(label);
  return svm::classNeighbourhoods(scaled, labels, ids, svm::Kernel::rbfFromSigma(sigma),
                                  0.5 / static_cast<double>(ids.size()));
}
// The roadmap's configurations along `nodes`, a path provenPath has checked (and proven, with a
// certifier), as the solved result.
void takePath(const Roadmap& roadmap, const std::vector<int>& nodes, const PlanningContext& context,
              PlanResult& result) {
  for (int v : nodes) result.path.push_back(roadmap.node(v));
  result.certified = context.certifier != nullptr;
  result.status = PlanStatus::kSolved;
}
}  // namespace

SvmpPlanner::SvmpPlanner(const PlanningContext& context, SvmpOptions options)
    : Planner(context),
      obstacle_group_(context.checker.environment().nestedGroups()),
      inner_obstacles_(context.checker.environment().innerObstacles(obstacle_group_)),
      options_(options.resolvedFor(context.space, planners::obstacleTrees(context, options, inner_obstacles_))) {
  if (const std::string err = options.validate(); !err.empty()) throw std::invalid_argument("svmp: " + err);
  if (options_.duplicate_radius < 0) options_.duplicate_radius = 0.5 * options_.step;
}

void SvmpPlanner::clear() {
  forgetBuild();
  samples_ = {};
  risk_.reset();
  roadmap_.clear();
  with_query_.clear();
  grown_by_trees_.clear();
  nn_.reset();
  uncentred_.clear();
  eager_pass_run_ = false;
  tree_answers_ = 0;
}

int SvmpPlanner::supportVectors() const {
  if (!risk_) return 0;
  int n = 0;
  for (int k = 0; k < risk_->numClasses(); ++k) n += risk_->model(k).numSupportVectors();
  return n;
}

int SvmpPlanner::obstacleTrees() const { return planners::obstacleTrees(context_, options_, inner_obstacles_); }

PlannerView SvmpPlanner::view() const { return {&samples_, risk(), &roadmap_}; }

std::map<std::string, std::string> SvmpPlanner::derivedParameters() const {
  using cspace::parameterText;
  return {{"sigma", parameterText(options_.sigma)},
          {"step", parameterText(options_.step)},
          {"samples_per_tree", std::to_string(options_.samples_per_tree)},
          {"tree_range", parameterText(options_.tree_range)},
          {"duplicate_radius", parameterText(options_.duplicate_radius)},
          {"descent_step", parameterText(options_.descent().max_step)},
          {"fk_sigma", parameterText(fkSigma())}};
}

double SvmpPlanner::fkSigma() const {
  // The FK kernel's width in the workspace: 5% of the arm's reach from its first joint.
  const Eigen::VectorXd& reach = context_.checker.robot().jointReach();
  return options_.fk_sigma > 0 ? options_.fk_sigma : reach.size() > 0 && reach[0] > 0 ? 0.05 * reach[0] : 0.1;
}

bool SvmpPlanner::sampleObstacle(std::uint64_t seed, PhaseTimes& times, const Termination& stop) {
  const auto t0 = Clock::now();
  planners::ObstacleSamplerOptions opt;
  opt.step = options_.step;
  opt.samples_per_tree = options_.samples_per_tree;
  opt.include_self_collision = options_.sample_self_collision;
  opt.max_expansions_per_node = options_.tree_expansions_per_node;
  // Surfaces located to a quarter of the checking resolution: finer than any passage the motion
  // validator can tell apart, coarse enough to cost a few bisection checks per boundary node.
  opt.refine_tolerance = context_.validator.resolution() / 4;
  if (blocked_motion_) opt.blocked_motions = {{blocked_motion_->start, blocked_motion_->goal}};
  opt.stop = stop.asFunction();
  // Obstacles one inside another are one obstacle to learn: a shape given twice, or nested, as
  // classes of their own would ask the SVM to separate one region from itself (training 0.2 -> 85
  // ms on a corridor whose two blocks were each given ten times). Only the outermost are sampled.
  opt.skip = inner_obstacles_;
  samples_ = planners::sampleObstacles(context_.checker, context_.space, opt, seed, context_.threads);
  for (int& label : samples_.labels)
    if (label > 0) label = obstacle_group_[label - 1];
  // One obstacle (or only the self-collision region) sampled: the space's bounds are the other class,
  // so the boundary runs between the obstacle and the bounds, where paths round it.
  if (const std::set<int> labels(samples_.labels.begin(), samples_.labels.end()); labels.size() == 1)
    addBoundsSamples(context_.space, options_.samples_per_tree, seed, samples_);
  times.sampling_ms += msSince(t0);
  return !samples_.stopped;
}

std::string SvmpPlanner::trainMultiSvm(PhaseTimes& times, const Termination& stop) {
  if (samples_.size() == 0) throw std::logic_error("svmp: trainMultiSvm before sampleObstacle");
  const auto t0 = Clock::now();
  const cspace::Environment& env = context_.checker.environment();
  std::map<int, double> weights;
  for (int label : samples_.labels) weights[label] = label > 0 ? 0.0 : 1.0;
  for (const cspace::Obstacle& o : env.obstacles())  // a group's weight: the largest of its obstacles'
    if (const auto it = weights.find(obstacle_group_[o.id - 1]); it != weights.end() && !o.is_virtual)
      it->second = std::max(it->second, o.weight);
  if (weights.size() < 2) {
    const int only = weights.empty() ? 0 : weights.begin()->first;
    const std::string have = weights.empty() ? "none"
                             : only > 0      ? "only '" + env.byId(only).name + "'"
                                             : "only the self-collision region";
    return "svmp: one-versus-rest needs samples of at least two obstacles, got " + have +
           (samples_.warnings.empty() ? "" : " (" + samples_.warnings.front() + ")");
  }
  svm::SolverOptions solver;
  solver.eps = options_.eps;
  solver.cache_mb = options_.cache_mb;
  solver.stop = stop.asFunction();  // a solve the limit ends keeps its iterate; the build then times out
  // Every boundary sample, each obstacle's first sample (so no class is left without one) and an
  // evenly spread share of the interior ones (deterministic).
  std::vector<int> kept;
  std::set<int> seen;
  double due = 0.0;
  for (int i = 0; i < samples_.size(); ++i) {
    const bool first = seen.insert(samples_.labels[i]).second;
    if (!samples_.boundary[i] && !first) {
      due += options_.interior_fraction;
      if (due < 1.0) continue;
      due -= 1.0;
    }
    kept.push_back(i);
  }
  Eigen::MatrixXd points(samples_.points.rows(), static_cast<Eigen::Index>(kept.size()));
  std::vector<int> labels(kept.size());
  for (size_t j = 0; j < kept.size(); ++j) {
    points.col(static_cast<Eigen::Index>(j)) = samples_.points.col(kept[j]);
    labels[j] = samples_.labels[kept[j]];
  }
  const bool fk = options_.kernel == "fk";
  // Classes: one per obstacle, or colours of the obstacles' adjacency graph (weight: the largest of
  // the colour's obstacles, so no obstacle's penalty drops).
  std::vector<std::vector<int>> obstacle_hoods;
  bool colour = options_.classes == "colour";
  if (options_.classes == "auto" && weights.size() > 8) {
    if (!fk && options_.training != "full")
      obstacle_hoods = smallObstacleNeighbourhoods(context_.space.metricScale().asDiagonal() * points, labels,
                                                   weights, options_.sigma);
    colour = obstacle_hoods.empty();
  }
  class_of_label_.clear();
  if (colour) {
    class_of_label_ = colourClasses(samples_.points, samples_.labels, context_.space.metricScale(), 3 * options_.sigma);
    // No two obstacles adjacent: still two models (one-versus-rest needs a rest).
    bool one = true;
    for (const auto& [label, c] : class_of_label_) one = one && c == 1;
    if (one) class_of_label_.begin()->second = 2;
  } else
    for (const auto& [label, w] : weights) class_of_label_[label] = label;
  std::vector<int> classes(kept.size());
  for (size_t j = 0; j < kept.size(); ++j) classes[j] = class_of_label_.at(labels[j]);
  std::map<int, double> class_weights;
  for (const auto& [label, w] : weights) {
    double& cw = class_weights[class_of_label_.at(label)];
    cw = std::max(cw, w);
  }
  const robots::Robot& robot = context_.checker.robot();
  risk_.emplace(RiskFunction::trainOneVsRest(points, classes, fk ? fkSigma() : options_.sigma,
                                             options_.C, class_weights, solver, context_.space.metricScale(),
                                             options_.truncated, context_.threads,
                                             fk ? &robot : nullptr,
                                             options_.training == "full"            ? OvrTraining::kFull
                                             : options_.training == "neighbourhood" ? OvrTraining::kNeighbourhood
                                                                                    : OvrTraining::kAuto,
                                             obstacle_hoods.empty() ? nullptr : &obstacle_hoods));
  times.training_ms += msSince(t0);
  return "";
}

bool SvmpPlanner::makeRoadmap(PhaseTimes& times, const Termination& stop) {
  if (!risk_) throw std::logic_error("svmp: makeRoadmap before trainMultiSvm");
  const auto t0 = Clock::now();
  nn_.emplace(roadmap_.nodes(), context_.space.metricScale());
  const bool done = connectMilestones(roadmap_, *nn_, context_, options_.k, 0, stop, options_.lazy);
  times.roadmap_ms += msSince(t0);
  return done;
}

void SvmpPlanner::buildRoadmap(std::uint64_t seed, const Termination& stop, PlanResult& result) {
  PhaseTimes& times = result.times;
  const robots::Robot* fk = options_.kernel == "fk" ? &context_.checker.robot() : nullptr;
  if (const std::string why = RiskFunction::unsupported(context_.space.dim(), fk); !why.empty()) {
    result.status = PlanStatus::kInvalidInput;
    result.message = "svmp: " + why;
    return;
  }
  result.status = PlanStatus::kTimeout;
  result.message = "time limit reached while sampling obstacles";
  if (sampleObstacle(seed, times, stop)) {
    result.warnings = samples_.unsampled;
    if (samples_.size() == 0) {
      // No obstacle to learn (none, or none within reach): the roadmap stays empty and queries are
      // answered by the straight motion and the trees, never by a repair along a boundary.
      result.warnings.push_back("no obstacle was sampled, so there is no boundary to learn");
      nn_.emplace(roadmap_.nodes(), context_.space.metricScale());
      result.status = PlanStatus::kSolved;
      result.message.clear();
    } else if (result.message = trainMultiSvm(times, stop); !result.message.empty()) {
      result.status = PlanStatus::kInvalidInput;
    } else if (stop()) {
      result.status = PlanStatus::kTimeout;
      result.message = "time limit reached after training";
    } else if (!findBoundaryMilestones(times, stop)) {
      result.status = PlanStatus::kTimeout;
      result.message = "time limit reached while finding boundary milestones";
    } else if (!makeRoadmap(times, stop)) {
      result.status = PlanStatus::kTimeout;
      result.message = "time limit reached while connecting the roadmap";
    } else {
      result.status = PlanStatus::kSolved;
      result.message.clear();
    }
  }
  fillCounters(result);
}

void SvmpPlanner::fillCounters(PlanResult& result) const {
  result.milestones = roadmap_.numNodes();
  result.roadmap_edges = roadmap_.numEdges();
  result.support_vectors = supportVectors();
}

bool SvmpPlanner::joinByTrees(Roadmap& with_query, int start_node, int goal_node, int samples, cspace::Rng& rng,
                              const Termination& stop, PlanResult& result, TreeRoots from) {
  // The components hold the lazy roadmap's unchecked edges. Where the joined path does not hold, its
  // blocked edges are gone and the trees grow on from the components left, for as many samples as the
  // last join took, at least a tenth of them: a join found quickly is likely found again quickly
  // (panda_shelf's 100 queries, seed 1: its 6th query 15.3 -> 2.5 ms), one found late would cost as
  // much again where passages wind (crs6_partition); after a join in 2 samples, 3 grow too little
  // (Fig 4.4: 8% fewer checks with the tenth).
  // Their step adapts to the clutter (connectByTrees): with OMPL's fixed range a 4-link arm hooking
  // from one wall top to the other under a ceiling failed 6 of 20 seeds, and Fig 4.12's trees grew
  // 0-1 nodes in 450 samples (median 34 -> 6 ms; docs/dev-log.md, thirty-first session).
  const int first = std::max(start_node, goal_node) + 1;
  const int own = with_query.numNodes();  // this call's nodes from here on (an earlier call's stay)
  int linked = first;
  for (int left = samples; left > 0 && !stop();) {
    TreeStep step(options_.tree_range);  // afresh each call: panda_shelf's joins need the long steps
    const auto roots = [&](int end) {  // from the query's ends: the end and this call's nodes
      std::vector<int> nodes = with_query.component(end);
      if (from == TreeRoots::kQueryEnds) std::erase_if(nodes, [&](int v) { return v != end && v < own; });
      return nodes;
    };
    const TreeConnectResult grown =
        connectByTrees(with_query, roots(start_node), roots(goal_node), context_, options_.tree_range, left, rng, stop,
                       &step);
    // The joining sample counts too.
    left = std::min(left - grown.samples - 1, std::max(grown.samples + 1, samples / 10));
    if (!grown.connected) return false;
    // The trees' nodes are linked lazily to their k nearest milestones, as the lazy roadmap's own: the
    // search then leaves the trees' detours where a milestone offers a shorter way (paths 9-28% shorter
    // on the gaps and the Panda files, docs/dev-log.md, twelfth session). The nodes are new, so no
    // pair of theirs is blocked yet.
    for (int v = linked; v < with_query.numNodes(); ++v)
      for (int j : nn_->nearest(with_query.node(v), options_.k))
        if (!with_query.hasEdge(v, j))
          with_query.addEdge(v, j, context_.space.distance(with_query.node(v), with_query.node(j)), false);
    linked = with_query.numNodes();
    int checks = 0;
    const std::vector<int> nodes = provenPath(with_query, start_node, goal_node, context_, &roadmap_,
                                              checks, result.times.certify_ms);
    if (nodes.empty()) continue;
    takePath(with_query, nodes, context_, result);
    keepTreeNodes(with_query, first);
    ++tree_answers_;
    return true;
  }
  return false;
}

bool SvmpPlanner::answerBeforeBuild(const cspace::Query& query, std::uint64_t seed, const Termination& stop,
                                    PlanResult& result) {
  if (options_.trees_before_build <= 0) return false;
  const auto t0 = Clock::now();
  Roadmap trees;
  trees.addNode(query.start);
  trees.addNode(query.goal);
  cspace::Rng rng(seed ^ 0x3C3C3C3CULL);
  TreeStep step(options_.tree_range);
  const TreeConnectResult grown = connectByTrees(trees, {0}, {1}, context_, options_.tree_range,
                                                 options_.trees_before_build, rng, stop, &step);
  std::vector<int> nodes;
  if (grown.connected) {
    int checks = 0;
    nodes = provenPath(trees, 0, 1, context_, nullptr, checks, result.times.certify_ms);
  }
  result.times.query_ms += msSince(t0);
  // The trees' nodes and edges, as the rivals' trees are counted; a build that follows counts its own.
  result.milestones = trees.numNodes();
  result.roadmap_edges = trees.numEdges();
  if (!nodes.empty()) {
    takePath(trees, nodes, context_, result);
    result.message.clear();
    return true;
  }
  if (!stop()) return false;
  result.status = PlanStatus::kTimeout;
  result.message = "time limit reached while growing trees before the build";
  return true;
}

void SvmpPlanner::keepTreeNodes(const Roadmap& with_query, int first) {
  const int n = roadmap_.numNodes();
  const auto index = [&](int v) { return v < first ? v : n + v - first; };
  for (int v = first; v < with_query.numNodes(); ++v) roadmap_.addNode(with_query.node(v));
  std::vector<std::pair<int, Edge>> links;
  for (int v = first; v < with_query.numNodes(); ++v)
    for (Edge e : with_query.neighbours(v)) {
      // Not the edges to the query's ends; each edge between two tree nodes once.
      if ((e.to >= n && e.to < first) || (e.to >= first && e.to < v)) continue;
      e.to = index(e.to);
      if (!e.checked) {
        links.emplace_back(index(v), e);
        continue;
      }
      roadmap_.addEdge(index(v), e.to, e.cost);
      if (e.certified) roadmap_.markCertified(index(v), e.to);
    }
  // The unchecked links only within components: a later query's repair needs the components the
  // roadmap has proven (as after the eager pass).
  roadmap_.restoreWithinComponents(links);
  grown_by_trees_.resize(n, false);
  grown_by_trees_.resize(roadmap_.numNodes(), true);
  nn_->extend(roadmap_.nodes());
}

void SvmpPlanner::answer(const cspace::Query& query, std::uint64_t seed, const Termination& stop,
                         PlanResult& result) {
  const auto t0 = Clock::now();
  cspace::Rng rng(seed ^ 0xA5A5A5A5ULL), tree_rng(seed ^ 0x5A5A5A5AULL);
  repair_step_.emplace(options_.tree_range);
  std::string why = options_.repair_rounds == 0 ? "repair_rounds is 0" : "";  // why still not connected
  // A round that grows the start's or the goal's component is progress and costs no budget (up to
  // kMaxRoundsFactor x repair_rounds rounds in all); one without progress spends a round and doubles
  // the spread of the next round's samples (up to 8x). 8x stopped 5 of 4,380 runs (60 seeds, 73
  // files) that were still growing towards a window or along a tunnel; 32x solves all five
  // (docs/dev-log.md, "Repair that runs on while it grows").
  constexpr int kMaxRoundsFactor = 32;
  int spent = 0, last_size = -1;
  double widen = 1.0;
  RepairTrail trail;
  std::optional<Roadmap> before_repair;  // restored when the query fails (below)
  bool full_trees_tried = false;         // joinByTrees of lazy_trees samples, once per query
  bool try_straight = !blocked_motion_;
  // A limit that has fired ends the query, saying after how many repair rounds.
  const auto timedOut = [&](int round) {
    if (!stop()) return false;
    result.status = PlanStatus::kTimeout;
    result.message = "time limit reached after " + std::to_string(round) + " repair rounds";
    return true;
  };
  for (int round = 0;; ++round) {
    Roadmap& with_query = with_query_;
    with_query = roadmap_;
    QueryOutcome outcome =
        queryRoadmap(with_query, *nn_, context_, query, options_.k, &roadmap_, try_straight);
    try_straight = false;  // the rounds add milestones, not free space
    result.times.certify_ms += outcome.certify_ms;
    if (!outcome.path.empty()) {
      result.path = std::move(outcome.path);
      result.certified = outcome.certified;
      result.status = PlanStatus::kSolved;
      break;
    }
    // A limit that fired during the search (its checks were cut short) ends the query before the
    // repairs below change the shared roadmap on the strength of them.
    if (timedOut(round)) break;
    // A lazy roadmap that fails first tries the cheaper repairs first, each once per query and the
    // query run again as round 0 after each: trees of half the size (joinByTrees), the build's deferred
    // centred milestones linked lazily (often what a narrow passage needs: forest_200 checked 36% more
    // when they went straight into the eager pass), trees of full size, then the thesis' eager
    // MakeRoadmap (checked edges are kept), once per build. Trees first answered Fig 4.4 and panda_shelf
    // in 0.7x the time, where centring had been wasted on most failing seeds; at half size they cost
    // little where the centring answers (docs/dev-log.md, eighteenth session). Eager connection
    // reaches other components beyond the k nearest, and repair's frontiers need the components the
    // roadmap has proven.
    if (round == 0 && options_.lazy && !full_trees_tried) {
      const bool centring_pending = !uncentred_.empty();  // then half-size trees, before it
      full_trees_tried = !centring_pending;
      const int samples = centring_pending ? options_.lazy_trees / 2 : options_.lazy_trees;
      if (joinByTrees(with_query, outcome.start_node, outcome.goal_node, samples, tree_rng, stop, result)) break;
    }
    if (round == 0 && !uncentred_.empty()) {
      const int first = roadmap_.numNodes();
      if (centreDeferred() > 0) connectMilestones(roadmap_, *nn_, context_, options_.k, first, stop, true);
      --round;  // again, then the full-size trees, even when no end could be centred
      continue;
    }
    if (round == 0 && !eager_pass_run_ && roadmap_.hasUnchecked()) {
      eager_pass_run_ = true;
      const auto lazy = roadmap_.dropUnchecked();
      connectShortestFirst(roadmap_, *nn_, context_, options_.k, stop);
      // The lazy edges within the components the pass proved come back (later queries take them
      // where the pass's spanning forest goes round).
      roadmap_.restoreWithinComponents(lazy);
      --round;
      continue;
    }
    // Progress is the guided repair's: the trees' nodes grow the components every round.
    int start_size = 0, goal_size = 0, guided = 0;
    for (int i = 0; i < with_query.numNodes(); ++i) {
      const bool on_start = with_query.connected(i, outcome.start_node);
      const bool on_goal = with_query.connected(i, outcome.goal_node);
      start_size += on_start;
      goal_size += on_goal;
      guided += (on_start || on_goal) && (i >= static_cast<int>(grown_by_trees_.size()) || !grown_by_trees_[i]);
    }
    if (round > 0) {
      if (guided > last_size) {
        widen = 1.0;
      } else {
        ++spent;
        widen = std::min(8.0, 2.0 * widen);
      }
    }
    last_size = guided;
    const bool budget = spent < options_.repair_rounds && round < kMaxRoundsFactor * options_.repair_rounds;
    if (budget && !before_repair) before_repair.emplace(roadmap_);
    if (!risk_) why = "no obstacle was sampled, so no decision boundary guides a repair";
    const bool repaired =
        budget && risk_ && !stop() &&
        repair(with_query, outcome.start_node, outcome.goal_node, widen, trail, rng, tree_rng, stop, why,
               result.times.certify_ms);
    // Before a repaired query fails, trees ten times the size of those before the eager pass, then
    // twice, four and eight times that: the repair's rounds grow trees of repair_samples between
    // guided rounds, too small where the passage winds through many dimensions
    // (bench/unseen/crs6_partition: 3 of 60 seeds failed after 40 rounds, RRTConnect solved all 60;
    // an arm deep in a sleeve and a sphere in a building, where RRTConnect grows 23k nodes: 1 of 30
    // failed with one size). A bound of work, not of time: the same seed fails the same way under
    // any time limit, and a query no path answers costs about 15x one size's trees.
    // The sizes alternate between trees from the query's ends alone, as RRT-Connect grows them, and
    // trees from the whole components: components of 10k repair nodes along a wall offer every sample
    // beyond it a wall node as its nearest, so they reach a window 4e-4 of the wall's area only by
    // chance (a 3-D point in [0, 1000]^3, 1 of 20 seeds failed; RRTConnect solved all), while a winding
    // maze needs the components' reach (maze3d: 1 of 20 more failed from the ends alone). Alternating,
    // both are solved, and a failing query costs up to 14% less (Figs 2.10 and 4.10, --queries 100).
    constexpr int kLastTreesFactor = 10, kLastTreesDoublings = 3;
    if (!repaired && options_.repair_rounds > 0 && options_.lazy && options_.lazy_trees > 0 && !stop()) {
      const int first = kLastTreesFactor * options_.lazy_trees, last = first << kLastTreesDoublings;
      bool joined = false;
      bool from_ends = true;
      for (int samples = first; samples <= last && !joined && !stop(); samples *= 2, from_ends = !from_ends)
        joined = joinByTrees(with_query, outcome.start_node, outcome.goal_node, samples, tree_rng, stop, result,
                             from_ends ? TreeRoots::kQueryEnds : TreeRoots::kComponents);
      if (joined) break;
      why += std::string(why.empty() ? "" : "; ") + "trees of " + std::to_string(first) + " to " +
             std::to_string(last) + " uniform samples did not join them";
    }
    if (timedOut(round)) break;
    if (!repaired) {
      if (!budget && options_.repair_rounds > 0) {
        const std::string stopped =
            spent >= options_.repair_rounds
                ? std::to_string(spent) + " rounds without progress"
                : "the limit of " + std::to_string(kMaxRoundsFactor * options_.repair_rounds) + " rounds";
        why = why.empty() ? stopped : stopped + "; " + why;
      }
      result.status = PlanStatus::kFailed;
      result.message = "start and goal are not connected after " + std::to_string(round) +
                       " repair rounds (their components hold " + std::to_string(start_size) + " and " +
                       std::to_string(goal_size) + " of " + std::to_string(with_query.numNodes()) +
                       " nodes; " + why + ")";
      break;
    }
  }
  // A query that fails leaves the roadmap as its repair found it: a pair that no planner joins fills
  // both components with thousands of repair nodes, which would slow every later query and make the
  // next such pair dearer (ceiling_slot, 100 random pairs: 32k nodes and 35 s kept, 432 and 8.7 s so).
  if (!result.solved() && before_repair) {
    roadmap_ = std::move(*before_repair);
    grown_by_trees_.resize(std::min(grown_by_trees_.size(), static_cast<size_t>(roadmap_.numNodes())));
    nn_.emplace(roadmap_.nodes(), context_.space.metricScale());
  }
  result.times.query_ms += msSince(t0);
  fillCounters(result);
}

}  // namespace svmp::planners
