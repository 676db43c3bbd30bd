#include "planners/tree_connect.hpp"

#include <limits>
#include <utility>

namespace svmp::planners {

namespace {

// The trees are a few thousand nodes at most: a linear scan is cheaper than keeping an index.
int nearestIn(const Roadmap& roadmap, const std::vector<int>& tree, const Eigen::VectorXd& q,
              const cspace::ConfigurationSpace& space) {
  int best = -1;
  double best_d = std::numeric_limits<double>::infinity();
  for (int i : tree)
    if (const double d = space.distance(roadmap.node(i), q); d < best_d) best = i, best_d = d;
  return best;
}

// One checked step of at most `range` from node `from` towards q; the new node, or -1 when blocked.
int extend(Roadmap& roadmap, std::vector<int>& tree, int from, const Eigen::VectorXd& q,
           const PlanningContext& context, double range) {
  const Eigen::VectorXd next = context.space.steer(roadmap.node(from), q, range);
  if (!context.validator.isValid(roadmap.node(from), next)) return -1;
  const int node = roadmap.addNode(next);
  roadmap.addEdge(from, node, context.space.distance(roadmap.node(from), next));
  tree.push_back(node);
  return node;
}

}  // namespace

void TreeStep::record(bool free) {
  ++tried;
  held += free;
  if (tried < kWindow) return;
  if (held <= kMostFreeToHalve && range > longest / (1 << kMaxHalvings)) range /= 2;
  else if (2 * held > tried && range < longest) range *= 2;
  tried = held = 0;
}

TreeConnectResult connectByTrees(Roadmap& roadmap, std::vector<int> a, std::vector<int> b,
                                 const PlanningContext& context, double range, int samples, cspace::Rng& rng,
                                 const Termination& stop, TreeStep* step) {
  TreeConnectResult out;
  if (a.empty() || b.empty() || !(range > 0)) return out;
  const cspace::ConfigurationSpace& space = context.space;
  // Balanced (tree_connect.hpp): the tree that has grown fewer nodes in this search explores next,
  // the two in turn while they have grown as many.
  struct Tree {
    std::vector<int> nodes;
    size_t roots;  // the component it started from: nodes[0, roots)
    size_t grown() const { return nodes.size() - roots; }
  };
  const size_t roots_a = a.size(), roots_b = b.size();
  Tree first{std::move(a), roots_a}, second{std::move(b), roots_b};
  Tree *explore = &first, *join = &second;
  for (; out.samples < samples && !stop(); ++out.samples) {
    if (out.samples > 0 && join->grown() <= explore->grown()) std::swap(explore, join);
    if (step) range = step->range;
    const Eigen::VectorXd q = space.sampleUniform(rng);
    const int grown = extend(roadmap, explore->nodes, nearestIn(roadmap, explore->nodes, q, space), q, context, range);
    if (step) step->record(grown >= 0);
    if (grown < 0) continue;
    ++out.added;
    const Eigen::VectorXd target = roadmap.node(grown);
    for (int tip = nearestIn(roadmap, join->nodes, target, space);;) {
      const double gap = space.distance(roadmap.node(tip), target);
      if (gap <= range) {
        if (!context.validator.isValid(roadmap.node(tip), target)) break;
        roadmap.addEdge(tip, grown, gap);
        out.connected = true;
        return out;
      }
      tip = extend(roadmap, join->nodes, tip, target, context, range);
      if (tip < 0) break;
      ++out.added;
    }
  }
  return out;
}

}  // namespace svmp::planners
