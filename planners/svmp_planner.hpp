#pragma once
// SVMP, the global SVM-based planner of the thesis (ch. 3-4), with the steps of its Planner class
// (ch. 4.3.2): SampleObstacle (RRT-like trees inside each C-obstacle, Algorithm 1), TrainMultiSVM
// (one-versus-rest RBF SVMs, per-class C, ch. 3.2 and 4.1.2; on an arm each class on its
// neighbourhood with the bias fixed, svm/local_one_vs_rest.hpp), FindBoundaryMilestones (each boundary
// sample descends its class's risk function R_k = |F_k| to the decision boundary; kept when
// collision-free and not a near-duplicate), MakeRoadmap (k nearest in other components, union-find;
// by default with lazy edges, checked when a query's path uses them) and Query (A*). When a query fails, the thesis' future work (ch. 3.5): random configurations near the
// disconnection are guided down to the decision boundaries, the narrowest pairs are bridged along the
// boundary, and the roadmap is reconnected (answer, repair, bridge).
// The roadmap answers many queries: build() once, query() many times; clear() forgets it.
// Parameters (scenario `planners.svmp`, `--set svmp.KEY=VALUE`): the fields of SvmpOptions, same names.
// Thread safety: as every Planner (planners/planner.hpp); OpenMP inside over trees, descents, checks.
#include <map>
#include <optional>

#include "planners/obstacle_sampler.hpp"
#include "planners/nearest_neighbors.hpp"
#include "cspace/scenario/parameters.hpp"
#include "planners/planner.hpp"
#include "planners/risk_function.hpp"
#include "planners/roadmap.hpp"
#include "planners/tree_connect.hpp"

namespace svmp::planners {

struct SvmpOptions {
  // Unset (kDerived) sigma and step are derived from the space (resolvedFor): step 1/40 of the mean
  // weighted joint range, sigma twice the step (neighbouring samples' kernels overlap, thesis
  // ch. 4.1.1). Over the 33 files in bench/scenarios this matched the hand-picked values' success;
  // passages much narrower than sigma are found by centring (centreAlongNormal) and repair's bridges.
  static constexpr double kDerived = -1;
  double sigma = kDerived;        // RBF width in the weighted metric, gamma = 1/(2 sigma^2)
  double C = 100;                 // penalty; obstacle weights scale it per class
  double step = kDerived;         // obstacle sampling step (weighted metric)
  // Unset (kDerived): kSamplesPerTree a tree while the trees hold at most kSampleBudget samples in
  // all, then kSampleBudget / trees, at least kMinSamplesPerTree (resolvedFor). Then the samples, and
  // the training that grows faster than they do, stop growing with the obstacle count: arms among
  // 30-60 small boxes trained for 113-152 ms on 200 a tree, 12-14 ms on 39-77 a tree, at the same
  // success, with colour classes (docs/dev-log.md, "An arm in clutter"; one model per obstacle
  // has since cut that to 2-4 ms).
  static constexpr int kSamplesPerTree = 200, kSampleBudget = 2400, kMinSamplesPerTree = 20;
  int samples_per_tree = static_cast<int>(kDerived);
  int k = 10;                     // roadmap neighbours
  // Lazy roadmap edges (LazyPRM, Bohlin and Kavraki 2000; roadmap_builder.hpp): the thesis checks
  // every edge while connecting, which was 40-50% of a single query's time on Figs 4.4-4.10; lazily,
  // a query checks only the edges on its candidate paths. false: the thesis' eager MakeRoadmap.
  bool lazy = true;
  double eps = 1e-3;              // SMO stopping tolerance
  double cache_mb = 100;
  bool truncated = true;          // exp(-5)-truncated evaluation of F
  double descent_tolerance = 1e-3;  // |F| at which a descent counts as on the boundary
  double descent_step = -1;       // longest descent step (weighted metric); <= 0: sigma
  int descent_iterations = 100;
  double duplicate_radius = -1;   // milestones closer than this are merged; < 0: step / 2
  // Query repair rounds without progress allowed (0 disables repair); a round that grows the start's
  // or goal's component costs none, up to 32 x repair_rounds rounds in all (fewer stopped runs whose
  // components were still growing; docs/dev-log.md, "Repair that runs on while it grows").
  int repair_rounds = 5;
  int repair_samples = 100;       // random configurations per repair round
  // When the lazy roadmap did not answer a query, RRT-Connect trees between the start's and the
  // goal's components for up to lazy_trees samples (0: none), their nodes linked lazily to their k
  // nearest milestones and, when they answer, kept in the roadmap; before the build's eager pass and
  // before any repair round (and ten times as large before a repaired query fails). Where the build's
  // centring is still deferred, trees of half the size come first, then the centring, then these
  // (Fig 4.4 and panda_shelf 0.7x the time; eighteenth session). On the arms the eager pass costs
  // 25k-65k checks where trees join in a few thousand (panda_shelf 1.5x, Fig 4.4 1.1x faster, paths
  // shorter; docs/dev-log.md, twelfth session), and a repair round 15k-35k where the trees join
  // a pocket the roadmap does not reach in 1k-2k (panda_shelf, 100 queries: 0.57-0.79x the time;
  // fourteenth session).
  int lazy_trees = 300;
  // A single query (solve) whose straight motion is blocked first grows RRT-Connect trees between
  // start and goal, their step adapting (TreeStep), for up to this many samples; where they join,
  // the path is proven and returned with no obstacle sampled. 0, the default: the thesis' method,
  // which learns the obstacles before it plans. With 300, over 90 bench files (20 seeds) the trees
  // answered most seeds of 41 and single queries took 0.29x the time (geometric mean of medians;
  // 14 files, the narrow passages, 1.1-1.6x), but svmp's numbers would then measure RRT-Connect
  // wherever it succeeds, not SVMP (docs/dev-log.md, "Trees before the build").
  int trees_before_build = 0;
  // A repair round whose guided nodes do not join the start's and the goal's components then grows
  // RRT-Connect trees from both (planners/tree_connect.hpp; first, when either holds at most k roadmap
  // nodes): repair_samples uniform samples, steps of
  // at most tree_range (weighted metric; kDerived: OMPL's default range for RRTConnect, a fifth of
  // the space's diagonal), shortened while nearly every step collides (TreeStep).
  bool repair_trees = true;
  double tree_range = kDerived;
  // Share of the interior (non-boundary) obstacle samples the SVMs train on; every boundary sample
  // is kept. Interior samples far from other classes are rarely support vectors yet cost training
  // time; 0.1 cut panda_shelf's training from 45% to 21% of its time at the same success (Fig 4.4:
  // 10 -> 15 of 20; docs/dev-log.md), 0-0.1 measured alike.
  double interior_fraction = 0.1;
  // An obstacle tree thinner than the step stops after this many expansions a node
  // (planners::ObstacleSamplerOptions::max_expansions_per_node); 0: the thesis' trees, which grow on.
  int tree_expansions_per_node = ObstacleSamplerOptions{}.max_expansions_per_node;
  bool centre_in_passage = true;  // see SvmpPlanner::centreAlongNormal
  // With lazy edges, the build's descent ends that collide are centred when a query first fails on
  // the lazy roadmap, and linked lazily, not while building: centring was 2/3 of the milestone phase
  // on Figs 4.4-4.10, whose single queries need none of those nodes; narrow passages (the gap
  // family) get them at their first query (docs/dev-log.md, "Centring when a query needs it").
  bool defer_centring = true;
  bool sample_self_collision = true;  // the self-collision region is one more class
  // "rbf": the thesis' RBF on the weighted joints; "fk": the FK kernel of Das & Yip 2019 (eq. 4), the
  // RBF of width fk_sigma (m) on each control point's workspace position, summed over control points;
  // fk_sigma <= 0: 5% of the robot's reach (the reach of its first joint).
  std::string kernel = "rbf";
  double fk_sigma = -1;
  // One-versus-rest classes: "obstacle" (the thesis: one per obstacle and the self-collision region),
  // "colour" (obstacles whose samples come within 3 sigma share a model only if not adjacent,
  // planners/class_colouring.hpp), "auto" (colour above 8 classes, so the thesis' cases keep theirs,
  // unless per-obstacle neighbourhoods are cheaper: SvmpPlanner::trainMultiSvm).
  std::string classes = "auto";
  // One-versus-rest training: "full" (the thesis' C-SVC on every sample, bias free),
  // "neighbourhood" (each class on its samples and those within the kernel's truncation radius, bias
  // fixed at -1: svm/local_one_vs_rest.hpp) or "auto" (neighbourhoods where they are small enough to
  // pay: planners/risk_function.hpp). The FK kernel always trains "full".
  std::string training = "auto";

  // Reads every field from `params` under its own name, with its bounds; absent keys keep the
  // defaults above (the one place they are written). Throws cspace::ScenarioError.
  static SvmpOptions fromParameters(const cspace::ParameterSet& params);
  // "" when usable, else what is wrong.
  std::string validate() const;
  // These options with sigma, step and samples_per_tree derived where unset; `trees`: how many
  // obstacle trees the sampling grows (real obstacles not inside another, and the self-collision region).
  SvmpOptions resolvedFor(const cspace::ConfigurationSpace& space, int trees) const;
  // The milestone descent with descent_step resolved.
  DescentOptions descent() const;
  bool operator==(const SvmpOptions&) const = default;
};

class SvmpPlanner final : public Planner {
 public:
  // Throws std::invalid_argument when options.validate() fails.
  SvmpPlanner(const PlanningContext& context, SvmpOptions options);
  std::string name() const override { return "svmp"; }
  void clear() override;
  PlannerView view() const override;
  std::map<std::string, std::string> derivedParameters() const override;
  double fkSigma() const;  // fk_sigma, or its default from the robot's reach
  // The trees the obstacle sampling grows: one per real obstacle not inside another, and one in the
  // self-collision region when it is sampled.
  int obstacleTrees() const;

  // The steps of build(), callable one by one; each adds its time to `times`. Out of order they throw
  // std::logic_error. sampleObstacle returns false when `stop` ended it; trainMultiSvm returns "" or
  // why it cannot train (fewer than two classes sampled; sampleObstacle adds the bounds as the second
  // class, and buildRoadmap does not train with none); `stop` ends its solves where they are, and
  // buildRoadmap then reports the time limit.
  bool sampleObstacle(std::uint64_t seed, PhaseTimes& times, const Termination& stop = {});
  std::string trainMultiSvm(PhaseTimes& times, const Termination& stop = {});
  bool findBoundaryMilestones(PhaseTimes& times, const Termination& stop = {});
  bool makeRoadmap(PhaseTimes& times, const Termination& stop = {});

  const planners::ObstacleSamples& samples() const { return samples_; }
  const RiskFunction* risk() const { return risk_ ? &*risk_ : nullptr; }
  const Roadmap& roadmap() const { return roadmap_; }
  int supportVectors() const;
  const SvmpOptions& options() const { return options_; }
  // Whether this build's eager pass ran (once, at the first query the lazy roadmap and the trees
  // before it did not answer).
  bool eagerPassRun() const { return eager_pass_run_; }
  // Queries of this build answered by trees (SvmpOptions::lazy_trees): those before the eager pass
  // and the repair, or the larger ones before a repaired query fails.
  int treeAnswers() const { return tree_answers_; }
  // Descent ends whose centring is still deferred (until a query needs them).
  int pendingCentring() const { return static_cast<int>(uncentred_.size()); }

 protected:
  bool triesStraightMotionFirst() const override { return true; }
  void buildRoadmap(std::uint64_t seed, const Termination& stop, PlanResult& result) override;
  bool answerBeforeBuild(const cspace::Query& query, std::uint64_t seed, const Termination& stop,
                         PlanResult& result) override;
  void answer(const cspace::Query& query, std::uint64_t seed, const Termination& stop,
              PlanResult& result) override;

 private:
  void fillCounters(PlanResult& result) const;
  // Descends each start point on the risk of its class (or, with class -1, of the nearest boundary)
  // and adds the collision-free, non-duplicate results as milestones. With keep_free_starts, each free
  // start is a milestone too (the repair's hybrid with uniform PRM sampling that thesis ch. 3.5
  // suggests where obstacle regions dominate). duplicate_radius < 0: the option's. Returns how many
  // were added; stops early (returning what it added) when `stop` fires.
  // With defer_centring, ends that collide are kept in uncentred_ instead of being centred.
  int addMilestones(const std::vector<Eigen::VectorXd>& starts, const std::vector<int>& classes,
                    const Termination& stop, bool keep_free_starts = false, double duplicate_radius = -1,
                    bool defer_centring = false);
  // Centres the deferred ends (centreAlongNormal) and adds those found free as milestones; returns
  // how many. The roadmap's index is rebuilt when any was added.
  int centreDeferred();
  // What a query's repair rounds remember of the rounds before.
  struct RepairTrail {
    std::pair<Eigen::VectorXd, Eigen::VectorXd> last_between;  // the closest pair between the components
    std::vector<Eigen::VectorXd> visited;  // midpoints of the pairs the rounds repaired at
  };
  // One repair round; false when no round can help (`why` says so); `why` also keeps why the last
  // round added nothing. `trail` is updated. The trees draw from tree_rng, so the guided samples'
  // draws do not depend on them. Proofs it runs add their time to certify_ms.
  bool repair(Roadmap& with_query, int start_node, int goal_node, double widen, RepairTrail& trail,
              cspace::Rng& rng, cspace::Rng& tree_rng, const Termination& stop, std::string& why,
              double& certify_ms);
  // Links `a` (roadmap node a_node, or -1 for a query's endpoint) to node b_node along the decision
  // boundary: a blocked segment is split at a tangent step from either end or at its middle pulled
  // onto the boundary, each placed in the passage (inPassage), recursively. Straight segments between
  // milestones rarely thread a passage much narrower than sigma at its mouths, where the smooth
  // boundary strays from the passage's centre. Returns how many milestones it added.
  int bridge(const Eigen::VectorXd& a, int a_node, int b_node);
  int nearestBoundary(const Eigen::VectorXd& q) const;  // the class k whose |F_k(q)| is smallest
  // q centred along grad F_k (centreAlongNormal) unless centre_in_passage is off; then q when free.
  std::optional<Eigen::VectorXd> inPassage(int k, const Eigen::VectorXd& q) const;
  // A descended milestone that collides lies where the SVM boundary, smooth at the scale sigma, misses
  // a passage narrower than sigma. Along the boundary's normal (grad F_k) within sigma, find the free
  // interval nearest to it (doubling steps from resolution/4, then bisection of both edges) and return
  // its middle: the centre of the passage on that line. Empty when no free interval is found. A free
  // q is centred in its own interval when that is bounded within sigma on both sides (a passage
  // narrower than 2 sigma), else returned as it is.
  std::optional<Eigen::VectorXd> centreAlongNormal(int k, const Eigen::VectorXd& q) const;
  // RRT-Connect trees of up to `samples` samples on the query roadmap: true, with result's path, when
  // they join the start's and the goal's components and a path between them holds its proofs (a join
  // whose path fails grows on, up to as many samples again as it took, at least a tenth of `samples`).
  // The trees' step adapts to the clutter (connectByTrees). They grow from the whole components, or
  // from the query's ends and the nodes this call grew alone.
  enum class TreeRoots { kComponents, kQueryEnds };
  bool joinByTrees(Roadmap& with_query, int start_node, int goal_node, int samples, cspace::Rng& rng,
                   const Termination& stop, PlanResult& result, TreeRoots from = TreeRoots::kComponents);
  // Adds the query roadmap's nodes from `first` on (after the milestones and the query's ends) to the
  // roadmap, with their edges except those to the query's ends.
  void keepTreeNodes(const Roadmap& with_query, int first);

  // Properties of the immutable environment, found once: obstacle id - 1 -> its sample label
  // (Environment::nestedGroups), and the obstacles not sampled (Environment::innerObstacles).
  // Declared before options_, which derives its samples per tree from the trees left.
  const std::vector<int> obstacle_group_;
  const std::vector<char> inner_obstacles_;
  SvmpOptions options_;
  planners::ObstacleSamples samples_;
  std::optional<RiskFunction> risk_;
  Roadmap roadmap_;
  Roadmap with_query_;  // roadmap_ plus a query's endpoints; assigned anew per round, keeping its allocations
  std::optional<NearestNeighbors> nn_;
  std::vector<bool> grown_by_trees_;  // roadmap_ nodes the repair's trees added (by index; shorter: no)
  std::map<int, int> class_of_label_;  // sample label -> the risk function's class label
  std::vector<std::pair<Eigen::VectorXd, int>> uncentred_;  // deferred descent ends and their classes
  // The step the repair's trees adapt (connectByTrees), carried across a query's rounds: a round's
  // 100 samples are fewer than one window.
  std::optional<TreeStep> repair_step_;
  bool eager_pass_run_ = false;    // eagerPassRun()
  int tree_answers_ = 0;           // treeAnswers()
};

}  // namespace svmp::planners
