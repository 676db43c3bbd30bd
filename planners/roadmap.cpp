#include "planners/roadmap.hpp"

#include <algorithm>

namespace svmp::planners {

void UnionFind::resize(int n) {
  const int old = size();
  parent_.resize(n);
  rank_.resize(n, 0);
  for (int i = old; i < n; ++i) parent_[i] = i;
}

int UnionFind::find(int a) {
  while (parent_[a] != a) {
    parent_[a] = parent_[parent_[a]];  // path halving
    a = parent_[a];
  }
  return a;
}

bool UnionFind::unite(int a, int b) {
  a = find(a);
  b = find(b);
  if (a == b) return false;
  if (rank_[a] < rank_[b]) std::swap(a, b);
  parent_[b] = a;
  if (rank_[a] == rank_[b]) ++rank_[a];
  return true;
}

int Roadmap::addNode(const Eigen::VectorXd& q) {
  nodes_.push_back(q);
  adjacency_.emplace_back();
  components_.resize(numNodes());
  return numNodes() - 1;
}

void Roadmap::addEdge(int a, int b, double cost, bool checked) {
  adjacency_[a].push_back({b, cost, false, checked});
  adjacency_[b].push_back({a, cost, false, checked});
  components_.unite(a, b);
  ++num_edges_;
}

namespace {
std::uint64_t pairKey(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(a) << 32) | static_cast<std::uint32_t>(b);
}
}  // namespace

bool Roadmap::isBlocked(int a, int b) const {
  return std::binary_search(blocked_.begin(), blocked_.end(), pairKey(a, b));
}

void Roadmap::removeEdge(int a, int b) {
  const std::uint64_t key = pairKey(a, b);
  if (const auto at = std::lower_bound(blocked_.begin(), blocked_.end(), key); at == blocked_.end() || *at != key)
    blocked_.insert(at, key);
  auto drop = [this](int from, int to) {
    auto& list = adjacency_[from];
    const auto it = std::find_if(list.begin(), list.end(), [to](const Edge& e) { return e.to == to; });
    if (it == list.end()) return false;
    list.erase(it);
    return true;
  };
  if (!drop(a, b)) return;
  drop(b, a);
  --num_edges_;
  stale_ = true;
}

std::vector<std::pair<int, Edge>> Roadmap::dropUnchecked() {
  std::vector<std::pair<int, Edge>> dropped;
  for (int a = 0; a < numNodes(); ++a)
    for (const Edge& e : adjacency_[a])
      if (!e.checked && a < e.to) dropped.emplace_back(a, e);
  for (auto& list : adjacency_) std::erase_if(list, [](const Edge& e) { return !e.checked; });
  num_edges_ -= static_cast<int>(dropped.size());
  stale_ = true;
  return dropped;
}

void Roadmap::restoreWithinComponents(const std::vector<std::pair<int, Edge>>& edges) {
  for (const auto& [a, e] : edges)
    if (connected(a, e.to) && !hasEdge(a, e.to)) addEdge(a, e.to, e.cost, false);
}

bool Roadmap::hasUnchecked() const {
  return std::any_of(adjacency_.begin(), adjacency_.end(), [](const std::vector<Edge>& list) {
    return std::any_of(list.begin(), list.end(), [](const Edge& e) { return !e.checked; });
  });
}

std::vector<int> Roadmap::component(int node) {
  std::vector<int> nodes;
  for (int i = 0; i < numNodes(); ++i)
    if (connected(i, node)) nodes.push_back(i);
  return nodes;
}

void Roadmap::recomputeComponents() {
  components_ = UnionFind(numNodes());
  stale_ = false;
  for (int u = 0; u < numNodes(); ++u)
    for (const Edge& e : adjacency_[u])
      if (u < e.to) components_.unite(u, e.to);
}

void Roadmap::mark(int a, int b, bool certified) {
  for (auto [from, to] : {std::pair{a, b}, std::pair{b, a}})
    for (Edge& e : adjacency_[from])
      if (e.to == to) e.checked = true, e.certified = e.certified || certified;
}

void Roadmap::markChecked(int a, int b) { mark(a, b, false); }
void Roadmap::markCertified(int a, int b) { mark(a, b, true); }

const Edge* Roadmap::find(int a, int b) const {
  for (const Edge& e : adjacency_[a])
    if (e.to == b) return &e;
  return nullptr;
}

bool Roadmap::hasEdge(int a, int b) const { return find(a, b) != nullptr; }

bool Roadmap::isChecked(int a, int b) const {
  const Edge* e = find(a, b);
  return e && e->checked;
}

bool Roadmap::isCertified(int a, int b) const {
  const Edge* e = find(a, b);
  return e && e->certified;
}

void Roadmap::clear() {
  nodes_.clear();
  adjacency_.clear();
  blocked_.clear();
  components_.resize(0);
  stale_ = false;
  num_edges_ = 0;
}

}  // namespace svmp::planners
