#include "planners/roadmap_builder.hpp"

namespace svmp::planners {

Connector straightConnector(const PlanningContext& context) {
  return [&context](Roadmap& roadmap, int a, int b) {
    if (!context.validator.isValid(roadmap.node(a), roadmap.node(b))) return false;
    roadmap.addEdge(a, b, context.space.distance(roadmap.node(a), roadmap.node(b)));
    return true;
  };
}

void connectMilestones(Roadmap& roadmap, const NearestNeighbors& nn, const PlanningContext& context,
                       int k, int first, const Connector& given) {
  const Connector connect = given ? given : straightConnector(context);
  const int count = roadmap.numNodes();  // nodes a connector adds on the way are not revisited
  // Ask the tree for more than k so that k remain after dropping same-component neighbours.
  const int search = std::min(nn.size(), 3 * k + 1);
  for (int i = first; i < count; ++i) {
    int tried = 0;
    for (int j : nn.nearest(roadmap.node(i), search)) {
      if (tried >= k) break;
      if (j == i || roadmap.connected(i, j)) continue;
      ++tried;
      connect(roadmap, i, j);
    }
  }
}

QueryOutcome queryRoadmap(Roadmap& roadmap, const NearestNeighbors& nn, const PlanningContext& context,
                          const cspace::Query& query, int k, const Connector& given) {
  const Connector connect = given ? given : straightConnector(context);
  QueryOutcome out;
  out.start_node = roadmap.addNode(query.start);
  out.goal_node = roadmap.addNode(query.goal);
  if (context.validator.isValid(query.start, query.goal))
    roadmap.addEdge(out.start_node, out.goal_node, context.space.distance(query.start, query.goal));
  for (int endpoint : {out.start_node, out.goal_node}) {
    int tried = 0;
    for (int j : nn.nearest(roadmap.node(endpoint), std::min(nn.size(), 3 * k))) {
      if (tried >= k) break;
      if (roadmap.connected(endpoint, j)) continue;
      ++tried;
      connect(roadmap, endpoint, j);
    }
  }
  if (!roadmap.connected(out.start_node, out.goal_node)) return out;
  const Eigen::VectorXd goal = query.goal;
  const auto nodes = roadmap.shortestPath(out.start_node, out.goal_node, [&](int v) {
    return context.space.distance(roadmap.node(v), goal);
  });
  for (int v : nodes) out.path.push_back(roadmap.node(v));
  return out;
}

double pathLength(const std::vector<Eigen::VectorXd>& path, const cspace::ConfigurationSpace& space) {
  double length = 0;
  for (size_t i = 1; i < path.size(); ++i) length += space.distance(path[i - 1], path[i]);
  return length;
}

}  // namespace svmp::planners
