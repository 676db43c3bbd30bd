#pragma once
// Roadmap construction and queries shared by SVMP (thesis ch. 3.3) and the classical PRM (Kavraki et al.
// 1996): each milestone is connected to its k nearest milestones that lie in other connected components
// (straight-line local planner at the scenario's resolution, union-find for components); a query
// connects start and goal to their k nearest milestones and runs A* on the roadmap.
#include "planners/nearest_neighbors.hpp"
#include "planners/planner.hpp"
#include "planners/roadmap.hpp"

namespace svmp::planners {

// Connects nodes [first, numNodes) of the roadmap; `nn` indexes the roadmap's nodes [0, nn.size()).
// Returns false when `stop` ended it early. Lazy (LazyPRM, Bohlin and Kavraki 2000): no motion is
// checked here; each node gets unchecked edges to its k nearest nodes and to nodes of other
// components among its 3k + 1 nearest (up to 2k edges), and queries check only the edges their
// paths use. A single query then checks tens to hundreds of motions (50-400 on Figs 4.4-4.10) instead
// of thousands.
bool connectMilestones(Roadmap& roadmap, const NearestNeighbors& nn, const PlanningContext& context,
                       int k, int first = 0, const Termination& stop = {}, bool lazy = false);

// connectMilestones (eager) over every indexed node in order of length, as Kruskal's algorithm: each
// node paired with its 3k + 1 nearest, all pairs shortest first, each checked when its nodes lie in
// different components and either has tried fewer than k pairs (a pair a query found blocked counts
// as tried, unchecked). Both build a spanning forest of the pairs found free; in node order a node
// whose nearest share its component reaches further, and a free edge's check costs its length
// (SVMP's eager pass after a failed lazy query: up to 30% fewer collision checks, docs/dev-log.md).
bool connectShortestFirst(Roadmap& roadmap, const NearestNeighbors& nn, const PlanningContext& context, int k,
                          const Termination& stop = {});

struct QueryOutcome {
  std::vector<Eigen::VectorXd> path;  // empty when start and goal are not connected
  int start_node = -1, goal_node = -1;  // their indices in the query roadmap
  bool certified = false;             // every edge of the path proven free by context.certifier
  double certify_ms = 0;              // time spent proving edges
  int lazy_checks = 0;                // unchecked edges the search made it check
};

// The shortest path from `from` to `to` whose every edge is checked (unchecked edges are checked,
// `checks` counting them) and, with context.certifier, proven (`certify_ms` adding the time); an edge
// that fails is removed, also from `milestones` when both its nodes are among milestones' nodes, and
// the search runs again. Empty when none is left.
std::vector<int> provenPath(Roadmap& roadmap, int from, int to, const PlanningContext& context, Roadmap* milestones,
                            int& checks, double& certify_ms);

// Adds start and goal to `roadmap` (the caller passes a copy when the roadmap must stay clean); when
// the straight motion between them is free and proven, that is the path (not tried with
// `try_straight` false: the caller knows it fails). Otherwise connects each to
// its k nearest milestones (checked edges, proven too with a certifier) and searches the path
// (provenPath): each unchecked edge of the path found is checked, and with context.certifier each
// edge is proven free (once: checked and proven edges are marked); an edge that fails is removed and
// the search runs again, until a path holds or start and goal are disconnected. `milestones`, the
// roadmap `roadmap` was copied from, gets the same marks and removals for edges between its nodes.
// `lazy_checks` counts the motions checked.
QueryOutcome queryRoadmap(Roadmap& roadmap, const NearestNeighbors& nn, const PlanningContext& context,
                          const cspace::Query& query, int k, Roadmap* milestones = nullptr,
                          bool try_straight = true);

}  // namespace svmp::planners
