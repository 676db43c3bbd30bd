#include "planners/roadmap_builder.hpp"

#include <algorithm>
#include <tuple>

namespace svmp::planners {

namespace {

// The certifier's proof of a-b, its time added to certify_ms.
bool prove(const PlanningContext& context, const Eigen::VectorXd& a, const Eigen::VectorXd& b, double& certify_ms) {
  const auto t0 = Clock::now();
  const bool proven = context.certifier->isValid(a, b);
  certify_ms += msSince(t0);
  return proven;
}

// The straight-line local planner: one validated segment, one edge. With a certifier and
// `certify_ms`, the segment must be proven too (the edge is marked certified, the proof's time added).
bool connect(Roadmap& roadmap, const PlanningContext& context, int a, int b, double* certify_ms) {
  const Eigen::VectorXd &qa = roadmap.node(a), &qb = roadmap.node(b);
  if (!context.validator.isValid(qa, qb)) return false;
  const bool proving = certify_ms && context.certifier;
  if (proving && !prove(context, qa, qb, *certify_ms)) return false;
  roadmap.addEdge(a, b, context.space.distance(qa, qb));
  if (proving) roadmap.markCertified(a, b);
  return true;
}

// Tries `node` against up to k of its `search` nearest indexed nodes that lie in other components (a
// pair a query found blocked counts as tried, without checking it again).
void connectToNearest(Roadmap& roadmap, const NearestNeighbors& nn, const PlanningContext& context,
                      int node, int k, int search) {
  int tried = 0;
  for (int j : nn.nearest(roadmap.node(node), search)) {
    if (tried >= k) break;
    if (j == node || roadmap.connected(node, j)) continue;
    ++tried;
    if (!roadmap.isBlocked(node, j)) connect(roadmap, context, node, j, nullptr);
  }
}

// Unchecked edges from `node` to its k nearest and to other components' nodes among `search`.
void linkToNearest(Roadmap& roadmap, const NearestNeighbors& nn, const PlanningContext& context, int node,
                   int k, int search) {
  int rank = 0, edges = 0;
  for (int j : nn.nearest(roadmap.node(node), search)) {
    if (j == node) continue;
    const bool near = rank++ < k;
    if (edges >= 2 * k || (!near && roadmap.connected(node, j)) || roadmap.hasEdge(node, j)) continue;
    roadmap.addEdge(node, j, context.space.distance(roadmap.node(node), roadmap.node(j)), false);
    ++edges;
  }
}

// A query's endpoint (not in the index): as connectToNearest over its 3k nearest, but while it has no
// edge it keeps trying past k.
// Each edge is proven when made (with a certifier): an endpoint joined by an edge that passes the
// sampled check but not the proof would seem to belong to a component it cannot reach, and the repair
// would look for the disconnection in the wrong place.
void connectEndpoint(Roadmap& roadmap, const NearestNeighbors& nn, const PlanningContext& context, int node,
                     int k, double& certify_ms) {
  int tried = 0, edges = 0;
  for (int j : nn.nearest(roadmap.node(node), std::min(nn.size(), 3 * k))) {
    if (tried >= k && edges > 0) break;
    if (roadmap.connected(node, j)) continue;
    ++tried;
    edges += connect(roadmap, context, node, j, &certify_ms);
  }
}

}  // namespace

bool connectMilestones(Roadmap& roadmap, const NearestNeighbors& nn, const PlanningContext& context,
                       int k, int first, const Termination& stop, bool lazy) {
  // Ask the tree for more than k so that k remain after dropping same-component neighbours.
  const int search = std::min(nn.size(), 3 * k + 1);
  for (int i = first; i < roadmap.numNodes(); ++i) {
    if (stop()) return false;
    lazy ? linkToNearest(roadmap, nn, context, i, k, search) : connectToNearest(roadmap, nn, context, i, k, search);
  }
  return true;
}

bool connectShortestFirst(Roadmap& roadmap, const NearestNeighbors& nn, const PlanningContext& context, int k,
                          const Termination& stop) {
  const int search = std::min(nn.size(), 3 * k + 1);
  std::vector<std::tuple<double, int, int>> pairs;
  for (int i = 0; i < nn.size(); ++i)
    for (int j : nn.nearest(roadmap.node(i), search))
      if (j != i) pairs.emplace_back(context.space.distance(roadmap.node(i), roadmap.node(j)), std::min(i, j), std::max(i, j));
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  std::vector<int> tries(roadmap.numNodes(), 0);
  int since_stop_check = 0;
  for (const auto& [length, i, j] : pairs) {
    if (++since_stop_check % 64 == 0 && stop()) return false;
    if ((tries[i] >= k && tries[j] >= k) || roadmap.connected(i, j)) continue;
    ++tries[i], ++tries[j];
    if (!roadmap.isBlocked(i, j)) connect(roadmap, context, i, j, nullptr);
  }
  return true;
}

constexpr int kScreenLevels = 2;  // provenPath's cheap passes: the midpoint, then the quarter points
// Searches after which provenPath screens every unchecked edge's midpoint at once, and twice as many
// after which it screens their quarter points (below).
constexpr int kSearchesBeforeScreeningAll = 32;

std::vector<int> provenPath(Roadmap& roadmap, int from, int to, const PlanningContext& context, Roadmap* milestones,
                            int& checks, double& certify_ms) {
  const int shared = milestones ? milestones->numNodes() : 0;
  const Eigen::VectorXd target = roadmap.node(to);
  // The searches repeat after each removal (hundreds of times on the arms' lazy roadmaps); the
  // heuristic of a node does not change between them.
  std::vector<double> heuristic(roadmap.numNodes(), -1.0);
  Roadmap::SearchScratch scratch;
  Eigen::VectorXd point(target.size());
  int level = 1;  // the points of a bisection level: odd multiples of 2^-level
  const auto levelFree = [&](const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
    const int parts = 1 << level;
    for (int i = 1; i < parts; i += 2) {
      context.space.interpolate(a, b, static_cast<double>(i) / parts, point);
      if (!context.checker.isValid(point)) return false;
    }
    return true;
  };
  // Removes the edge u-v, from the shared roadmap too; not once the time limit has fired
  // (cspace::MotionStopScope): a check it cut short proves nothing, the shared roadmap serves later
  // queries, and a failure that was real is found again by them.
  const auto remove = [&](int u, int v) {
    if (cspace::MotionStopScope::stopped()) return;
    roadmap.removeEdge(u, v);
    if (milestones && u < shared && v < shared) milestones->removeEdge(u, v);
  };
  for (int searches = 1;; ++searches) {
    if (cspace::MotionStopScope::stopped()) return {};  // the time limit: the caller reports it
    // A search removes one or two failing edges; on the arms' lazy roadmaps a query that then fails
    // searched hundreds of times, each search a pass over the whole roadmap (Fig 4.4: 260-310
    // searches, 5-8 ms, against 2-3k collision checks). Past a few dozen searches every unchecked
    // edge's midpoint is checked at once, a check per edge, and the failures removed; past twice as
    // many, their quarter points: edges across a board thinner than a tenth of their length pass the
    // midpoint (a point robot between shelf compartments 0.05 thick: 110-252 searches a run, 43% of
    // svmp's time, then 76-107; docs/dev-log.md, thirty-third session).
    if (searches % kSearchesBeforeScreeningAll == 0 && searches / kSearchesBeforeScreeningAll <= kScreenLevels) {
      std::vector<std::pair<int, int>> failed;
      level = searches / kSearchesBeforeScreeningAll;
      for (int u = 0; u < roadmap.numNodes(); ++u)
        for (const Edge& e : roadmap.neighbours(u))
          if (!e.checked && e.to > u && !levelFree(roadmap.node(u), roadmap.node(e.to))) failed.emplace_back(u, e.to);
      for (const auto& [u, v] : failed) remove(u, v);
    }
    const auto nodes = roadmap.shortestPath(from, to, [&](int v) {
      double& h = heuristic[v];
      if (h < 0) h = context.space.distance(roadmap.node(v), target);
      return h;
    }, scratch);
    if (nodes.empty()) return nodes;
    // One pass over the path's edges not yet `done`: each that passes `test` is marked (by `mark`,
    // when given), each that fails is removed (from the shared roadmap too). `whole`: the pass goes
    // on after a failure.
    const auto pass = [&](auto done, auto test, auto mark, bool whole) {
      bool all = true;
      for (size_t i = 0; i + 1 < nodes.size(); ++i) {
        const int u = nodes[i], v = nodes[i + 1];
        if ((roadmap.*done)(u, v)) continue;
        const bool free = test(roadmap.node(u), roadmap.node(v));
        if (!free)
          remove(u, v);
        else if (mark)
          for (Roadmap* r : {&roadmap, u < shared && v < shared ? milestones : nullptr})
            if (r) (r->*mark)(u, v);
        all = all && free;
        if (!all && !whole) return false;
      }
      return all;
    };
    // Unchecked edges first (cheap, and most failures are there), then the proofs. The check passes
    // cover the whole path: a sampled check of an edge costs a few collision checks, far less than
    // the search that each failure would otherwise cost (forest_200: query 9.1 -> 3.9 ms). As LazyPRM
    // (Bohlin and Kavraki 2000) checks at increasing resolution, every unchecked edge's midpoint
    // comes first, then its quarter points (kScreenLevels bisection levels), then the full check:
    // most failing edges fail early, and the full checks of the edges that pass are not spent on a
    // path that then fails (Figs 4.4-4.10: 12-23% fewer collision checks with the midpoint, Fig 4.6
    // 18% fewer again with the quarters; a third level gained no more elsewhere).
    constexpr void (Roadmap::*kNoMark)(int, int) = nullptr;
    const auto check = [&](const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
      ++checks;
      return context.validator.isValid(a, b);
    };
    const auto certify = [&](const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
      return prove(context, a, b, certify_ms);
    };
    bool screened = true;
    for (level = 1; level <= kScreenLevels && screened; ++level)
      screened = pass(&Roadmap::isChecked, levelFree, kNoMark, true);
    const bool disproved =
        !screened ||
        !pass(&Roadmap::isChecked, check, &Roadmap::markChecked, true) ||
        (context.certifier && !pass(&Roadmap::isCertified, certify, &Roadmap::markCertified, false));
    if (!disproved) return nodes;
  }
}

QueryOutcome queryRoadmap(Roadmap& roadmap, const NearestNeighbors& nn, const PlanningContext& context,
                          const cspace::Query& query, int k, Roadmap* milestones, bool try_straight) {
  QueryOutcome out;
  out.start_node = roadmap.addNode(query.start);
  out.goal_node = roadmap.addNode(query.goal);
  // The straight motion first: when it is free and proven it is the shortest path there is, and the
  // endpoints' connections to the roadmap (long motions on an arm: about 300 checks each on
  // panda_shelf) are not needed.
  if (try_straight && connect(roadmap, context, out.start_node, out.goal_node, &out.certify_ms)) {
    out.path = {query.start, query.goal};
    out.certified = context.certifier != nullptr;
    return out;
  }
  for (int endpoint : {out.start_node, out.goal_node})
    connectEndpoint(roadmap, nn, context, endpoint, k, out.certify_ms);
  // The components answer the first time; then the search itself tells when the removed edges
  // disconnected the two (no path), without rebuilding the components after each removal.
  if (!roadmap.connected(out.start_node, out.goal_node)) return out;
  const std::vector<int> nodes = provenPath(roadmap, out.start_node, out.goal_node, context, milestones,
                                            out.lazy_checks, out.certify_ms);
  for (int v : nodes) out.path.push_back(roadmap.node(v));
  out.certified = !nodes.empty() && context.certifier != nullptr;
  return out;
}

}  // namespace svmp::planners
