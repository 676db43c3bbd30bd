#pragma once
// The roadmap shared by SVMP and the classical PRM: milestones, weighted undirected edges, union-find
// over connected components, and A* search (Hart, Nilsson, Raphael 1968) with the metric as heuristic.
// Edges may be added unchecked (lazy, as LazyPRM: Bohlin and Kavraki 2000); edges a query finds in
// collision are removed, and those checked or proven free are marked so later queries reuse the work.
// Components count unchecked edges: they are what the roadmap may connect, not what it has proven.
// Thread safety: none; one planner owns it.
#include <Eigen/Core>
#include <algorithm>
#include <cstdint>
#include <functional>
#include <limits>
#include <utility>
#include <vector>

namespace svmp::planners {

class UnionFind {
 public:
  explicit UnionFind(int n = 0) { resize(n); }
  void resize(int n);
  int find(int a);
  // Returns false when a and b were already in one component.
  bool unite(int a, int b);
  bool same(int a, int b) { return find(a) == find(b); }
  int size() const { return static_cast<int>(parent_.size()); }

 private:
  std::vector<int> parent_, rank_;
};

struct Edge {
  int to;
  double cost;
  bool certified = false;  // proven collision-free by the certified validator (lazy, on first use)
  bool checked = true;     // passed the sampled motion validator; false: a lazy edge, unchecked yet
};

class Roadmap {
 public:
  // Adds a milestone; returns its index.
  int addNode(const Eigen::VectorXd& q);
  // checked = false adds a lazy edge (LazyPRM): assumed free until a query checks it.
  void addEdge(int a, int b, double cost, bool checked = true);
  bool hasEdge(int a, int b) const;
  // Removes the edge a-b (both directions); no-op when absent. The components are recomputed when
  // next asked for (a lazy query removes edges one by one and needs them only when its search fails).
  // The pair is remembered as blocked: edges are removed when their motion fails, and the eager pass
  // after a failed lazy query would otherwise check the same motions again.
  void removeEdge(int a, int b);
  bool isBlocked(int a, int b) const;
  // Removes every unchecked edge; returns them, each once (from the lower node's list).
  std::vector<std::pair<int, Edge>> dropUnchecked();
  // Adds, unchecked, those of `edges` whose nodes already lie in one component: they join nothing
  // new, and later searches take them where the checked edges go round.
  void restoreWithinComponents(const std::vector<std::pair<int, Edge>>& edges);
  bool hasUnchecked() const;
  void markChecked(int a, int b);
  void markCertified(int a, int b);  // certified implies checked
  bool isChecked(int a, int b) const;
  bool isCertified(int a, int b) const;
  void clear();

  int numNodes() const { return static_cast<int>(nodes_.size()); }
  int numEdges() const { return num_edges_; }
  const Eigen::VectorXd& node(int i) const { return nodes_[i]; }
  const std::vector<Eigen::VectorXd>& nodes() const { return nodes_; }
  const std::vector<Edge>& neighbours(int i) const { return adjacency_[i]; }
  UnionFind& components() {
    if (stale_) recomputeComponents();
    return components_;
  }
  bool connected(int a, int b) { return components().same(a, b); }
  std::vector<int> component(int node);  // every node connected to `node`, ascending

  // What a search needs besides the roadmap; a caller that searches again and again (provenPath)
  // keeps one, so the searches allocate nothing.
  struct SearchScratch {
    std::vector<double> g;
    std::vector<int> parent;
    std::vector<char> closed;
    std::vector<std::pair<double, int>> open;  // a binary heap of (f = g + h, node), least f on top
  };
  // Shortest path from `from` to `to` as node indices (empty when none). `heuristic(i)` must not
  // overestimate the remaining cost to `to` (the metric distance does not). A template, so the
  // heuristic is inlined: it is called once per edge relaxed.
  template <class Heuristic>
  std::vector<int> shortestPath(int from, int to, Heuristic&& heuristic, SearchScratch& scratch) const;
  template <class Heuristic>
  std::vector<int> shortestPath(int from, int to, Heuristic&& heuristic) const {
    SearchScratch scratch;
    return shortestPath(from, to, heuristic, scratch);
  }

 private:
  const Edge* find(int a, int b) const;  // the edge a-b in a's list, or nullptr
  void mark(int a, int b, bool certified);  // checked, and certified when asked, both directions
  void recomputeComponents();

  std::vector<Eigen::VectorXd> nodes_;
  std::vector<std::vector<Edge>> adjacency_;
  UnionFind components_;
  std::vector<std::uint64_t> blocked_;  // sorted keys of removed pairs (pairKey)
  bool stale_ = false;  // an edge was removed since components_ was built
  int num_edges_ = 0;
};

template <class Heuristic>
std::vector<int> Roadmap::shortestPath(int from, int to, Heuristic&& heuristic, SearchScratch& scratch) const {
  const int n = numNodes();
  auto& [g, parent, closed, open] = scratch;
  g.assign(n, std::numeric_limits<double>::infinity());
  parent.assign(n, -1);
  closed.assign(n, 0);
  open.clear();
  const auto push = [&open](double f, int v) {
    open.emplace_back(f, v);
    std::push_heap(open.begin(), open.end(), std::greater<>());
  };
  g[from] = 0;
  push(heuristic(from), from);
  while (!open.empty()) {
    std::pop_heap(open.begin(), open.end(), std::greater<>());
    const int u = open.back().second;
    open.pop_back();
    if (closed[u]) continue;
    closed[u] = 1;
    if (u == to) break;
    for (const Edge& e : adjacency_[u]) {
      const double candidate = g[u] + e.cost;
      if (candidate < g[e.to]) {
        g[e.to] = candidate;
        parent[e.to] = u;
        push(candidate + heuristic(e.to), e.to);
      }
    }
  }
  if (!closed[to]) return {};
  std::vector<int> path;
  for (int v = to; v != -1; v = parent[v]) path.push_back(v);
  std::reverse(path.begin(), path.end());
  return path;
}

}  // namespace svmp::planners
