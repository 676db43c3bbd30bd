#pragma once
// Obstacle sampling of SVMP, thesis ch. 3.1 (Algorithm 1, read as the text describes it): one RRT-like
// tree per C-obstacle region, rooted at a configuration that hits that obstacle (given in the scenario
// or found by uniform sampling: one shared stream of draws serves every obstacle, since a check names
// the obstacle a draw hits), grown towards uniform random configurations by a fixed step in the
// weighted metric. q_new joins the tree when it hits the same obstacle; when it is free, or the first
// point beyond the obstacle's surface towards it is (a gap narrower than the step), the node it grew
// from, q_expansion, is marked a boundary sample (the thesis' "otherwise": q_new free); q_new is dropped.
// A step into another obstacle across no free space marks nothing: the surface there faces no free
// space (73 files, 60 seeds: every run solved, time 0.95x geometric mean, 0.53-1.61x;
// docs/dev-log.md, "Boundary samples face free space"). Each tree stops at N nodes (or when it
// stalls, max_idle_factor, or is thinner than the step, max_expansions_per_node).
// Surface refinement (on by default; the thesis' own future direction, ch. 3.5: "sampling methods that
// focus on boundary samples"): the first time a node is marked boundary, the segment from it to the free
// q_new is bisected down to refine_tolerance and the last colliding point joins the tree as a boundary
// sample. Surface samples put the SVM's maximum-margin boundary in the middle of a passage to within that
// tolerance, where interior tree nodes leave it off by up to half a step.
// Trees grow in parallel (OpenMP), each from its own generator seeded by (seed, obstacle id), so the
// result does not depend on the thread count.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "cspace/validity_checker.hpp"
#include "cspace/configuration_space.hpp"

namespace svmp::planners {

struct ObstacleSamplerOptions {
  double step = 0.1;             // expansion step in the weighted metric
  int samples_per_tree = 200;    // N
  // Uniform draws when searching for a root. An obstacle these miss fills under about 1/7,000 of the
  // space (95% confidence) and is left unsampled with a warning; queries still answer through lazy
  // checks, repair and proofs. The targets left by the shared searches share these draws (each
  // asked which obstacles it hits), so many obstacles no configuration reaches cost one search, not
  // one each (200 discs beyond an arm's joint limits: 867 -> 25 ms). The rarest root on the 68 files is
  // ceiling_slot's front plate (about 1 draw in 12k): unsampled in 8 of 40 seeds, all 40 solved.
  int max_root_attempts = 20000;
  int max_iterations_factor = 50;  // a tree gives up after factor * N expansions
  // ... or when it stalls: factor * max(20, nodes) expansions in a row that add no node and mark no
  // boundary. A tree that fills its C-obstacle (a small obstacle holds fewer than N samples a step
  // apart) grows on only by spending collision checks (forest_200: 2.3M checks for 40k samples);
  // halving the step instead gave the same success at 1.5-18x the time. The limit follows the
  // tree's size, not N: a small tree also stalls where few uniform targets fall near its obstacle,
  // and its interior nodes are not what the SVMs train on (interior_fraction). Against 2N idle
  // expansions: the same success on the 33 files, forest_200 43.6 -> 23.6 ms, panda_shelf 264 ->
  // 184 ms (docs/dev-log.md).
  int max_idle_factor = 2;
  // ... or when it is thin: more than factor * max(20, nodes) expansions in all. A C-obstacle thinner
  // than the step (a wall, a pillar, an arm's self-collision region) sends most expansions out, and
  // each new boundary node restarts the idle count, so such a tree went on at one node per 15-35
  // expansions (panda_shelf's self-collision tree: 6,232 expansions and 1,041 bisection checks for
  // its 400 nodes, against 470-690 expansions for each board's). 0 turns the limit off.
  int max_expansions_per_node = 8;
  // Motions known to cross obstacles (a query's straight start-goal motion, checked before the
  // build): obstacles the shared root search missed are looked for along each, a step apart (at most
  // max_root_attempts checks), before the last shared search (a pebble across a 20-link arm's
  // straight motion took 20,000 draws and a warning that asked for `sample:`).
  std::vector<std::pair<Eigen::VectorXd, Eigen::VectorXd>> blocked_motions;
  bool include_virtual = false;  // also sample virtual (guide) obstacles
  // Obstacles not sampled (index id - 1; empty: none): those inside another that is
  // (Environment::innerObstacles). A post given 1,000 times grew 1,000 trees of one region (880 ms).
  std::vector<char> skip;
  // Also grow a tree in the self-collision region (label kSelfCollisionHit): the thesis counts self
  // collision as a C-obstacle (IsMeetingConstraints inside IsCollidingWith, ch. 4.3.2). Only used when
  // the robot has self-collision pairs.
  bool include_self_collision = true;
  bool refine_boundary = true;   // bisect towards the obstacle surface at boundary nodes
  double refine_tolerance = -1;  // bisection stops below this length; < 0: step / 256
  // Asked every few expansions of every tree (from the growing threads at once: must be thread-safe);
  // true ends the sampling with what it has and ObstacleSamples::stopped set.
  std::function<bool()> stop;
  std::string validate() const;  // "" when valid, else what is wrong
};

struct ObstacleSamples {
  Eigen::MatrixXd points;        // dof x n, one sample per column
  std::vector<int> labels;       // obstacle id of each sample
  std::vector<char> boundary;    // 1 when the sample is a boundary sample
  std::vector<int> tree_sizes;   // per tree grown: the obstacles sampled in environment order, then the self-collision region
  std::vector<std::string> warnings;  // roots not found, trees that stopped early
  // The warnings of the obstacles left without a sample (one names all those out of reach, one all
  // those no draw hit, one the self-collision region).
  std::vector<std::string> unsampled;
  bool stopped = false;          // ObstacleSamplerOptions::stop ended the sampling
  int size() const { return static_cast<int>(labels.size()); }
  int numBoundary() const;
};

ObstacleSamples sampleObstacles(const cspace::ValidityChecker& checker, const cspace::ConfigurationSpace& space,
                                const ObstacleSamplerOptions& options, std::uint64_t seed,
                                int threads);

// Appends `count` boundary samples on the faces of the configuration space's box, labelled
// cspace::kJointLimitHit: the bounds as one more region to keep away from, as the local planner's
// joint-limit samples (thesis ch. 2.2.1). A face is drawn with probability proportional to its
// measure in the weighted metric, the point on it uniformly. SVMP adds them when the obstacles
// give it a single class, which one-versus-rest cannot separate from nothing.
void addBoundsSamples(const cspace::ConfigurationSpace& space, int count, std::uint64_t seed,
                      ObstacleSamples& samples);

}  // namespace svmp::planners
