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
                       int k, int first, const Termination& stop) {
  // Ask the tree for more than k so that k remain after dropping same-component neighbours.
  const int search = std::min(nn.size(), 3 * k + 1);
  for (int i = first; i < roadmap.numNodes(); ++i) {
    if (stop()) return false;
    connectToNearest(roadmap, nn, context, i, k, search);
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
    bool disproved = false;
    for (size_t i = 0; context.certifier && i + 1 < nodes.size() && !disproved; ++i) {
      const int u = nodes[i], v = nodes[i + 1];
      if (roadmap.isCertified(u, v)) continue;
      const auto t0 = Clock::now();
      const bool free = context.certifier->isValid(roadmap.node(u), roadmap.node(v));
      out.certify_ms += msSince(t0);
      free ? roadmap.markCertified(u, v) : roadmap.removeEdge(u, v);
      if (u < shared && v < shared) free ? milestones->markCertified(u, v) : milestones->removeEdge(u, v);
      disproved = !free;
    }
    if (disproved) continue;
    for (int v : nodes) out.path.push_back(roadmap.node(v));
    out.certified = context.certifier != nullptr;
    break;
  }
  return out;
}

}  // namespace svmp::planners
