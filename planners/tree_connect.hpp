#pragma once
// Joining two roadmap components by RRT-Connect (Kuffner and LaValle, ICRA 2000), with each component
// as one tree whose nodes are all roots, as the sampling-based roadmap of trees does (Plaku, Bekris,
// Chen, Ladd and Kavraki, IEEE T-RO 2005). Each uniform sample extends one tree by one step of
// `range` from its nearest node; the other tree then connects towards the new node step by step
// until it reaches it (the components are joined) or is blocked. The search is balanced (LaValle,
// Planning Algorithms, 2006, sec. 5.5.3): the tree that has grown fewer nodes in it explores next,
// the two in turn while they have grown as many. A tree stuck in a pocket fails most of its steps
// and so gets most of the samples, where a roadmap component in open space would have spent half
// of them growing where the roadmap already is (Fig 4.10: 9 of 20 goals had no free edge to the
// roadmap; trees that took turns each sample checked 1.4x as much, panda_shelf 2x;
// docs/dev-log.md, "Balanced trees"). SVMP's repair
// (planners/svmp_repair.cpp) runs it in a round whose SVM-guided nodes did not join the start's and
// the goal's components: where the decision boundaries do not lead through a passage, the trees
// still explore it.
// With a TreeStep, the step adapts to the clutter: halved (down to a sixteenth) while at most
// one of the last 128 exploring steps was free, doubled back while more than half were; an arm among
// close walls takes steps of OMPL's range (a fifth of the space's diagonal, 2.5 rad for four joints)
// that nearly all collide. The other tree's connecting steps take the same range (full-range
// connecting steps did not help panda_shelf). SVMP's query trees start each call at the full range;
// its repair's trees carry one TreeStep across a query's rounds, whose 100 samples are fewer than a
// window (carried in the query trees too, it cost panda_shelf 25% more checks). Halving
// after 32 steps with fewer than 2 free made panda_shelf's joins dearer (its rare long steps out of a
// shelf's pocket are what join the trees: mean checks 1.8x over 60 seeds; 1.03x so).
// Every motion is checked by the context's validator; new nodes and edges join the roadmap checked
// (the query proves the edges its path uses).
#include <vector>

#include "cspace/configuration_space.hpp"
#include "planners/planner.hpp"
#include "planners/roadmap.hpp"
#include "planners/termination.hpp"

namespace svmp::planners {

struct TreeConnectResult {
  int samples = 0;         // uniform samples drawn
  int added = 0;           // new nodes
  bool connected = false;  // the trees met: one edge joins the two components
};

// The step of adaptive trees (above), carried across calls: one query's trees share it.
struct TreeStep {
  explicit TreeStep(double longest) : range(longest), longest(longest) {}
  // Counts one exploring step; at the end of each window of kWindow, halves or doubles the range.
  void record(bool free);
  static constexpr int kWindow = 128, kMostFreeToHalve = 1, kMaxHalvings = 4;
  double range, longest;
  int tried = 0, held = 0;  // the current window's exploring steps, and how many were free
};

// Grows the trees from the roadmap nodes `a` and `b` (two components) for up to `samples` samples,
// with steps of `range`, or of `step`'s adapting range when given (which the call updates).
// Returns at once when either set is empty or range is not positive.
TreeConnectResult connectByTrees(Roadmap& roadmap, std::vector<int> a, std::vector<int> b,
                                 const PlanningContext& context, double range, int samples, cspace::Rng& rng,
                                 const Termination& stop = {}, TreeStep* step = nullptr);

}  // namespace svmp::planners
