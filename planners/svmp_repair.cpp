// SVMP's query repair (thesis ch. 3.5, future work; docs/dev-log.md "Repair along the decision
// boundary" and "Trees in repair"): each round takes the narrowest pairs of the disconnection,
// bridges them along the decision boundary, guides random samples around them down to the boundary,
// and where those do not join the start's and the goal's components grows RRT-Connect trees from both;
// trees go first when one component is an endpoint's pocket of at most k nodes.
#include <algorithm>
#include <functional>
#include <limits>
#include <optional>
#include <random>

#include "planners/roadmap_builder.hpp"
#include "planners/svmp_planner.hpp"
#include "planners/tree_connect.hpp"

namespace svmp::planners {

int SvmpPlanner::bridge(const Eigen::VectorXd& a, int a_node, int b_node) {
  constexpr int kMaxDepth = 8, kMaxSplits = 32;
  int splits = 0, added = 0;
  const DescentOptions descent = options_.descent();
  const Eigen::VectorXd& scale = context_.space.metricScale();
  // From `from` towards `to` within the boundary's tangent plane at `from`: inside a passage the
  // boundary runs along it, so this follows the passage out of its mouth.
  auto tangentStep = [&](const Eigen::VectorXd& from, const Eigen::VectorXd& to) -> std::optional<Eigen::VectorXd> {
    const int k = nearestBoundary(from);
    Eigen::VectorXd grad(from.size());
    risk_->decisionAndGradient(k, from, grad);
    Eigen::VectorXd normal = grad.cwiseQuotient(scale);
    if (!(normal.norm() > 0)) return std::nullopt;
    normal.normalize();
    Eigen::VectorXd x = (to - from).cwiseProduct(scale);
    x -= x.dot(normal) * normal;
    Eigen::VectorXd m = from + x.cwiseQuotient(scale);
    context_.space.clamp(m);
    return inPassage(k, m);
  };
  // The middle pulled onto the nearest boundary (centred in the passage when it collides there).
  auto boundaryMiddle = [&](const Eigen::VectorXd& pa, const Eigen::VectorXd& pb) {
    const Eigen::VectorXd middle = 0.5 * (pa + pb);
    const int k = nearestBoundary(middle);
    return inPassage(k, risk_->descend(k, middle, context_.space, descent).q);
  };
  // A segment is checked, then proved where the query will prove it (at a passage's mouth the sampled
  // check may cut a corner; proving a blocked segment first would cost far more).
  // A blocked a-b is split at a point nearer to both ends, and each half linked the same way. The
  // split point is tried as a tangent step from either end, then as the boundary middle.
  std::function<bool(const Eigen::VectorXd&, int, const Eigen::VectorXd&, int, int)> link =
      [&](const Eigen::VectorXd& pa, int ia, const Eigen::VectorXd& pb, int ib, int depth) {
        const double length = context_.space.distance(pa, pb);
        if (context_.validator.isValid(pa, pb) && (!context_.certifier || context_.certifier->isValid(pa, pb))) {
          if (ia >= 0 && ib >= 0) {
            roadmap_.addEdge(ia, ib, length);
            if (context_.certifier) roadmap_.markCertified(ia, ib);
          }
          return true;
        }
        if (depth == 0) return false;
        auto nearer = [&](const std::optional<Eigen::VectorXd>& m) {
          return m && context_.space.distance(pa, *m) < length && context_.space.distance(*m, pb) < length;
        };
        std::optional<Eigen::VectorXd> m;
        for (int attempt = 0; attempt < 3 && !nearer(m); ++attempt) {
          if (++splits > kMaxSplits) return false;
          m = attempt == 0 ? tangentStep(pb, pa) : attempt == 1 ? tangentStep(pa, pb) : boundaryMiddle(pa, pb);
        }
        if (!nearer(m)) return false;
        const int im = roadmap_.addNode(*m);
        ++added;
        return link(pa, ia, *m, im, depth - 1) && link(*m, im, pb, ib, depth - 1);
      };
  const Eigen::VectorXd b = roadmap_.node(b_node);  // a copy: link adds nodes, the roadmap reallocates
  link(a, a_node, b, b_node, kMaxDepth);
  return added;
}

bool SvmpPlanner::repair(Roadmap& with_query, int start_node, int goal_node, double widen, RepairTrail& trail,
                         cspace::Rng& rng, cspace::Rng& tree_rng, const Termination& stop, std::string& why,
                         double& certify_ms) {
  // Frontier of a component: its node closest to a node outside it. Random configurations around the
  // segment between the two are guided down to the decision boundaries (thesis ch. 3.5).
  const Eigen::VectorXd& scale = context_.space.metricScale();
  std::vector<Eigen::VectorXd> starts;
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  struct Frontier {
    int a, b;        // a node of with_query in the component, b a node of roadmap_ outside it
    double gap;      // their distance
    bool alone;      // a is an endpoint without edges
  };
  const int old_n = roadmap_.numNodes();
  // The roadmap's nodes before this round, split into the start's component, the goal's and the rest,
  // each part with its own k-d tree: each search below asks one or two parts, so every node is
  // indexed once a round, not once for each search that counts it as outside.
  struct Part {
    std::vector<int> ids;
    std::vector<Eigen::VectorXd> points;
    std::optional<NearestNeighbors> nn;
  };
  Part on_start, on_goal, rest;
  for (int j = 0; j < old_n; ++j) {
    Part& part = with_query.connected(start_node, j) ? on_start : with_query.connected(goal_node, j) ? on_goal : rest;
    part.ids.push_back(j);
    part.points.push_back(roadmap_.node(j));
  }
  for (Part* part : {&on_start, &on_goal, &rest})
    if (!part->ids.empty()) part->nn.emplace(part->points, scale);
  // For each node of with_query that is `inside`, its nearest roadmap node in the `outside` parts,
  // exact (a search among each node's nearest few missed a tunnel's nodes once the repair had filled
  // the space at its mouth); the closest pair first, and only the pairs within `reach` times its gap.
  // The searches skip what lies beyond reach times the closest gap so far (or `closest`, when known):
  // the exact search of every node was 45% of a long repair's time (double_window3d, 80 rounds of 20k
  // nodes). With `stride` > 1 only every stride-th inside node is searched.
  const auto pairsBetween = [&](const std::function<bool(int)>& inside, std::initializer_list<const Part*> outside,
                                double reach, int stride = 1,
                                double closest = std::numeric_limits<double>::infinity()) {
    std::vector<Frontier> pairs;
    for (int i = 0, seen = 0; i < with_query.numNodes(); ++i) {
      if (!inside(i) || seen++ % stride != 0) continue;
      Frontier pair{i, -1, std::numeric_limits<double>::infinity(), false};
      for (const Part* part : outside) {
        if (!part->nn) continue;
        // A little beyond, so that rounding in the search's own distance drops no pair.
        const int j = part->nn->nearestWithin(with_query.node(i), std::min(reach * closest, pair.gap) * (1 + 1e-9));
        if (j < 0) continue;
        const double gap = context_.space.distance(with_query.node(i), part->points[j]);
        if (gap < pair.gap) pair.b = part->ids[j], pair.gap = gap;
      }
      if (pair.b < 0) continue;
      pairs.push_back(pair);
      closest = std::min(closest, pair.gap);
    }
    // Stable: among pairs as close (a node the repair added twice: gap 0), the first node's.
    std::stable_sort(pairs.begin(), pairs.end(), [](const Frontier& x, const Frontier& y) { return x.gap < y.gap; });
    const auto beyond = std::upper_bound(pairs.begin(), pairs.end(), reach * closest,
                                         [](double g, const Frontier& f) { return g < f.gap; });
    pairs.erase(beyond, pairs.end());
    return pairs;
  };
  std::vector<Frontier> frontiers;
  for (int endpoint : {start_node, goal_node}) {
    const Part* other = endpoint == start_node ? &on_goal : &on_start;
    const auto pairs = pairsBetween([&](int i) { return with_query.connected(endpoint, i); }, {other, &rest}, 1.0);
    if (pairs.empty()) continue;
    frontiers.push_back(pairs.front());
    frontiers.back().alone = pairs.front().a == endpoint;
  }
  // The first roadmap node in the start's component and in the goal's, -1 when none; the two are one
  // component when a path between them failed its proofs.
  const Part& goal_part = with_query.connected(start_node, goal_node) ? on_start : on_goal;
  const int start_root = on_start.ids.empty() ? -1 : on_start.ids.front();
  const int goal_root = goal_part.ids.empty() ? -1 : goal_part.ids.front();
  // The closest pair between the start's and the goal's components: the nearest outside nodes may
  // lead into dead ends while the two grow along one passage towards each other.
  const auto on_start_side = [&](int i) { return with_query.connected(start_node, i); };
  const std::vector<Frontier> between = pairsBetween(on_start_side, {&on_goal}, 1.0);
  if (!between.empty()) {
    frontiers.push_back(between.front());
    // When it is last round's pair again, also one among the pairs within 4x its gap: the closest may
    // face the other component across a wall (a maze of tunnels) round after round, while the
    // components grow elsewhere (progress) and meet at a pair farther apart. The one farthest from
    // every pair repaired at so far: the rounds' own nodes crowd round the closest pair, so a pair
    // drawn at random came from there too (a wall with one window off the start-goal line: 40 rounds
    // at the wall's near part, bench/unseen/window3d seed 4).
    const Eigen::VectorXd &a = with_query.node(between.front().a), &b = roadmap_.node(between.front().b);
    const auto midpoint = [&](const Frontier& f) -> Eigen::VectorXd {
      return 0.5 * (with_query.node(f.a) + roadmap_.node(f.b));
    };
    const bool again = trail.last_between.first.size() == a.size() && trail.last_between.first == a &&
                       trail.last_between.second == b;
    trail.last_between = {a, b};
    if (!again) trail.visited.push_back(0.5 * (a + b));
    // The pairs of at most kMaxCandidates start nodes, evenly strided: where the components lie far
    // apart, 4x the closest gap takes in every node of the start's, and their searches were 40% of a
    // late round on Fig 4.12's unsolvable pairs (10k nodes; the closest pair repeats every round).
    constexpr double kWithin = 4;
    constexpr int kMaxCandidates = 1024;
    const int stride = 1 + static_cast<int>(on_start.ids.size()) / kMaxCandidates;
    const std::vector<Frontier> candidates =
        again ? pairsBetween(on_start_side, {&on_goal}, kWithin, stride, between.front().gap) : std::vector<Frontier>{};
    const Frontier* farthest = nullptr;
    double best = -1;
    for (const Frontier& f : candidates) {
      if (f.a == between.front().a && f.b == between.front().b) continue;
      const Eigen::VectorXd m = midpoint(f);
      double nearest = std::numeric_limits<double>::infinity();
      for (const Eigen::VectorXd& v : trail.visited) nearest = std::min(nearest, context_.space.distance(m, v));
      if (nearest > best) best = nearest, farthest = &f;
    }
    if (farthest) {
      frontiers.push_back(*farthest);
      trail.visited.push_back(midpoint(*farthest));
    }
  }
  double narrowest = std::numeric_limits<double>::infinity();
  for (const Frontier& f : frontiers) {
    narrowest = std::min(narrowest, f.gap);
    const Eigen::VectorXd a = with_query.node(f.a), b = roadmap_.node(f.b);
    // Local to the disconnection (the pair is its narrowest point), wider after rounds without
    // progress. An endpoint with no edge sits in a passage too thin for the roadmap's nodes to see:
    // its samples are drawn around it instead, narrower after each round without progress.
    const double spread = f.alone ? 0.5 * f.gap / widen : 0.5 * f.gap * widen;
    for (int s = 0; s < options_.repair_samples / 2; ++s) {
      Eigen::VectorXd q = f.alone ? a : Eigen::VectorXd(a + unit(rng) * (b - a));
      for (int d = 0; d < q.size(); ++d) q[d] += spread * normal(rng) / scale[d];
      context_.space.clamp(q);
      starts.push_back(q);
    }
  }
  if (starts.empty()) {
    why = "no node outside the start's and goal's components to guide samples towards";
    return false;
  }
  // RRT-Connect trees grown from both components (planners/tree_connect.hpp). Joined only counts when
  // a path between them holds its proofs: an edge that passes the sampled check but not the proof
  // (fastron_panda: of length 4-5) would otherwise skip the trees round after round.
  int added = 0, checks = 0;
  const auto joined = [&] {
    return roadmap_.connected(start_root, goal_root) &&
           !provenPath(roadmap_, start_root, goal_root, context_, nullptr, checks, certify_ms).empty();
  };
  const auto growTrees = [&] {
    const int first = roadmap_.numNodes();
    const TreeConnectResult trees =
        connectByTrees(roadmap_, roadmap_.component(start_root), roadmap_.component(goal_root), context_,
                       options_.tree_range, options_.repair_samples, tree_rng, stop, &*repair_step_);
    grown_by_trees_.resize(first, false);
    grown_by_trees_.resize(roadmap_.numNodes(), true);
    if (trees.added > 0) {
      added += trees.added;
      nn_->extend(roadmap_.nodes());
      connectMilestones(roadmap_, *nn_, context_, options_.k, first, stop);
    }
  };
  const bool trees = options_.repair_trees && start_root >= 0 && goal_root >= 0;
  // A component of at most k roadmap nodes is an endpoint's pocket that the roadmap barely reaches
  // (panda_shelf's random queries: an end in a shelf compartment, 1-20 nodes): trees grown out of it
  // join it in a few hundred checks, a guided round costs about 50 ms there. Between two large
  // components the guided nodes go first: they find the passage the roadmap missed, where the trees
  // find a longer way round (gap_0.002: paths 33% longer with trees first).
  int smaller = 0;
  if (trees) {
    int start_size = 0, goal_size = 0;  // in roadmap_, without the query's edges
    for (int j = 0; j < old_n; ++j) {
      start_size += roadmap_.connected(j, start_root);
      goal_size += roadmap_.connected(j, goal_root);
    }
    smaller = std::min(start_size, goal_size);
  }
  const bool trees_first = trees && smaller <= options_.k;
  if (trees_first && !stop()) {
    growTrees();
    if (joined()) {
      why.clear();
      return true;
    }
  }
  const int guided_begin = roadmap_.numNodes();
  for (const Frontier& f : frontiers) added += bridge(with_query.node(f.a), f.a < old_n ? f.a : -1, f.b);
  // Milestones as close as a quarter of the disconnection: a passage narrower than the usual
  // duplicate radius needs them.
  added += addMilestones(starts, std::vector<int>(starts.size(), -1), stop, true,
                         std::min(options_.duplicate_radius, 0.25 * narrowest));
  if (roadmap_.numNodes() > guided_begin) {
    nn_->extend(roadmap_.nodes());
    connectMilestones(roadmap_, *nn_, context_, options_.k, guided_begin, stop);
  }
  // Where the guided nodes did not join the two, the trees.
  if (trees && !trees_first && !stop() && !joined()) growTrees();
  if (added == 0) {
    why = "the last round's " + std::to_string(starts.size()) + " guided samples gave no new free milestone";
    return true;  // another round draws new samples
  }
  why.clear();
  return true;
}

}  // namespace svmp::planners
