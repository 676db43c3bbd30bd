#include "planners/roadmap_builder.hpp"

namespace svmp::planners {

namespace {

// The straight-line local planner: one validated segment, one edge.
bool connect(Roadmap& roadmap, const PlanningContext& context, int a, int b) {
  if (!context.validator.isValid(roadmap.node(a), roadmap.node(b))) return false;
  roadmap.addEdge(a, b, context.space.distance(roadmap.node(a), roadmap.node(b)));
  return true;
}

// Tries `node` against up to k of its `search` nearest indexed nodes that lie in other components.
void connectToNearest(Roadmap& roadmap, const NearestNeighbors& nn, const PlanningContext& context,
                      int node, int k, int search) {
  int tried = 0;
  for (int j : nn.nearest(roadmap.node(node), search)) {
    if (tried >= k) break;
    if (j == node || roadmap.connected(node, j)) continue;
    ++tried;
    connect(roadmap, context, node, j);
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
void connectEndpoint(Roadmap& roadmap, const NearestNeighbors& nn, const PlanningContext& context, int node,
                     int k) {
  int tried = 0, edges = 0;
  for (int j : nn.nearest(roadmap.node(node), std::min(nn.size(), 3 * k))) {
    if (tried >= k && edges > 0) break;
    if (roadmap.connected(node, j)) continue;
    ++tried;
    edges += connect(roadmap, context, node, j);
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

QueryOutcome queryRoadmap(Roadmap& roadmap, const NearestNeighbors& nn, const PlanningContext& context,
                          const cspace::Query& query, int k, Roadmap* milestones) {
  QueryOutcome out;
  out.start_node = roadmap.addNode(query.start);
  out.goal_node = roadmap.addNode(query.goal);
  for (int endpoint : {out.start_node, out.goal_node}) connectEndpoint(roadmap, nn, context, endpoint, k);
  // The straight motion last: added first, it would join the goal to the start's component, the goal
  // would skip every neighbour there, and certification disproving it would leave the goal alone.
  if (context.validator.isValid(query.start, query.goal))
    roadmap.addEdge(out.start_node, out.goal_node, context.space.distance(query.start, query.goal));
  const Eigen::VectorXd goal = query.goal;
  const int shared = milestones ? milestones->numNodes() : 0;
  while (roadmap.connected(out.start_node, out.goal_node)) {
    const auto nodes = roadmap.shortestPath(out.start_node, out.goal_node, [&](int v) {
      return context.space.distance(roadmap.node(v), goal);
    });
    // Unchecked edges first, up to the first that fails (cheap, and most failures are there), then
    // the proofs.
    auto shared_too = [&](int u, int v, auto mark) {
      mark(roadmap, u, v);
      if (u < shared && v < shared) mark(*milestones, u, v);
    };
    const auto remove = [](Roadmap& r, int u, int v) { r.removeEdge(u, v); };
    bool disproved = false;
    for (size_t i = 0; i + 1 < nodes.size() && !disproved; ++i) {
      const int u = nodes[i], v = nodes[i + 1];
      if (roadmap.isChecked(u, v)) continue;
      ++out.lazy_checks;
      if (context.validator.isValid(roadmap.node(u), roadmap.node(v)))
        shared_too(u, v, [](Roadmap& r, int a, int b) { r.markChecked(a, b); });
      else
        shared_too(u, v, remove), disproved = true;
    }
    for (size_t i = 0; context.certifier && i + 1 < nodes.size() && !disproved; ++i) {
      const int u = nodes[i], v = nodes[i + 1];
      if (roadmap.isCertified(u, v)) continue;
      const auto t0 = Clock::now();
      const bool free = context.certifier->isValid(roadmap.node(u), roadmap.node(v));
      out.certify_ms += msSince(t0);
      if (free)
        shared_too(u, v, [](Roadmap& r, int a, int b) { r.markCertified(a, b); });
      else
        shared_too(u, v, remove), disproved = true;
    }
    if (disproved) continue;
    for (int v : nodes) out.path.push_back(roadmap.node(v));
    out.certified = context.certifier != nullptr;
    break;
  }
  return out;
}

}  // namespace svmp::planners
