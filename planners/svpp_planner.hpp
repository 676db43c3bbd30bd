#pragma once
// Support Vector Path Planning (J. Miura, "Support Vector Path Planning", IROS 2006) for point robots
// in 2-D and 3-D, on our SMO solver. A path is the zero level V = 0 of an SVM separating the obstacles
// labelled positive from those labelled negative:
//   build   - obstacles as convex parts, overlapping ones merged (sec. III-C), their samples at vertices
//             and edge midpoints (2-D, III-B-3) or vertices, edges and faces (3-D, IV-B-2);
//             planners/svpp_obstacles.hpp
//   query   - the nominal line (2-D) or PCA nominal plane (3-D, IV-A), virtual obstacles at start and goal
//             (III-B-2, IV-B-1), the initial pattern by centroid side and guide samples (III-B-3/4,
//             IV-B-3; planners/svpp_labelling.hpp); for each pattern an RBF SVM (sec. II, III-B-5) and
//             the surface followed from start to goal (Fig. 3 in 2-D, the local plane fit of Fig. 5 in 3-D;
//             planners/svpp_path.hpp); other patterns by flipping one random obstacle of the last
//             pattern, new patterns only, until N_p patterns were tried and a path was found (III-B-6).
//             Each path found is checked by the context's motion validator; the shortest wins and is
//             proven by Planner::certify (the next shortest is tried when that fails): an unproven path
//             is never solved.
// Other robots and spaces of another dimension give kInvalidInput. Parameters (scenario
// `planners.svpp`): the fields of SvppOptions, same names. Every random choice flows from the query's
// seed. Thread safety: as every Planner (planners/planner.hpp); single-threaded inside.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "cspace/scenario/parameters.hpp"
#include "planners/planner.hpp"
#include "planners/risk_function.hpp"
#include "planners/svpp_labelling.hpp"
#include "planners/svpp_path.hpp"
#include "svm/solver_workspace.hpp"

namespace svmp::planners {

struct SvppOptions {
  static constexpr int kPaperPatterns2d = 20, kPaperPatterns3d = 10;
  // Unset (kDerived) lengths and gamma are the paper's values scaled to the problem (resolvedFor):
  // lengths by s, gamma by 1 / s^2. The paper adjusts them "according to the space size" (sec.
  // III-C), for fields of equal obstacles about 0.45 (2-D) and 0.74 (3-D) apart; s is the smaller of
  // the space's mean side / 2 and the obstacles' mean spacing, (volume / count)^(1/dim), over the
  // paper's. So its problems keep its values, a scaled problem gets the scaled path, and the kernel
  // resolves neighbouring obstacles in a denser or sparser field.
  static constexpr double kDerived = -1, kPaperSide = 2;
  static constexpr double kPaperSpacing2d = 0.4472135954999579;  // (2 x 2 / 20)^(1/2)
  static constexpr double kPaperSpacing3d = 0.7368062997280773;  // (2 x 2 x 2 / 20)^(1/3)
  static constexpr double kPaperVirtualDistance = 0.05, kPaperGuideDistance = 0.2,
                          kPaperGuideSpacing = 0.1, kPaperStep = 0.05, kPaperGamma = 10;
  int virtual_samples = 3;                // N_v
  double virtual_distance = kDerived;     // d_v
  double guide_distance = kDerived;       // d_g
  double guide_spacing = kDerived;        // d_p
  int patterns = 0;                // N_p; 0: the paper's, 20 in 2-D and 10 in 3-D
  int max_patterns = 200;          // patterns tried at most while no path was found
  double search_angle_deg = 120;   // theta_s
  double step = kDerived;          // d_s
  // Step limit of one surface following; 0: 3 |goal - start| / d_s (a path three times the straight
  // line's length; the paper gives no number).
  int max_steps = 0;
  // SVM^light's -g: k(a, b) = exp(-gamma |a - b|^2); the paper's "size of Gaussian kernel is 10".
  double gamma = kDerived;
  double C = 1000;    // soft-margin weight (the paper's gamma of eq. 6)
  double eps = 1e-3;  // SMO stopping tolerance (SVM^light's default)

  static SvppOptions fromParameters(const cspace::ParameterSet& params);
  // Throws cspace::ScenarioError naming the field when `params` set a key the `dim`-D method never
  // reads (search_angle_deg beyond 2-D), rather than take a value that changes nothing.
  static void requireKeysFor(const cspace::ParameterSet& params, int dim);
  std::string validate() const;  // "" when usable
  // validate(), and the resolved lengths bounded in `space`: at most kMaxStepsPerDiagonal steps
  // across its diagonal (the paper's step makes 57), kMaxGuideSamples guide samples (a bound over
  // every query) and kMaxVirtualSamples virtual ones (4 N_v^(dim - 1)), so no setting makes a
  // training set or a surface following that memory or minutes cannot hold (a step 1e-6 of the
  // diagonal, or N_v = 100 in 3-D, ran for minutes).
  static constexpr double kMaxStepsPerDiagonal = 1e4, kMaxGuideSamples = 50000, kMaxVirtualSamples = 5000;
  std::string validateFor(const cspace::ConfigurationSpace& space) const;
  bool operator==(const SvppOptions&) const = default;
  // These options with every kDerived value scaled to `space` holding `obstacles` obstacles.
  SvppOptions resolvedFor(const cspace::ConfigurationSpace& space, int obstacles) const;
  int patternsFor(int dim) const {
    return patterns > 0 ? patterns : dim == 2 ? kPaperPatterns2d : kPaperPatterns3d;
  }
  SampleLayout layout() const;
  SurfaceFollowing following(const cspace::Query& query, const Eigen::VectorXd& lower,
                             const Eigen::VectorXd& upper) const;
};

// One obstacle pattern tried: its training set, SVM and surface following.
struct SvppTrial {
  Pattern pattern;
  TrainingSet samples;
  svm::BinaryModel model;
  FollowResult follow;
  bool valid = false;  // reached the goal and every segment passed the motion validator
  double svm_ms = 0, path_ms = 0;
};

// What one query did, for pictures and the timing tables.
struct SvppTrace {
  std::vector<SvppObstacle> obstacles;  // merged, pattern entries in this order
  NominalFrame frame;
  std::vector<SvppTrial> trials;
  int chosen = -1;  // index of the returned path's trial
};

// Trains the RBF SVM of one training set (per-sample C all equal). Throws std::invalid_argument
// when the set has one class only. `workspace`: kept between a query's patterns, its kernel cache's
// memory is reused instead of taken afresh (and faulted in) by every solve. `stop` (polled by the
// solver) may end the solve early: the caller then discards the model.
svm::BinaryModel trainSvppModel(const TrainingSet& set, double gamma, double C, double eps,
                                svm::SolverWorkspace* workspace = nullptr, const std::function<bool()>& stop = {});

class SvppPlanner final : public Planner {
 public:
  // Throws std::invalid_argument when options.validate() fails.
  SvppPlanner(const PlanningContext& context, SvppOptions options);
  std::string name() const override { return "svpp"; }
  bool repairable() const override { return false; }  // other patterns are its alternatives
  void clear() override;
  void clearQuery() override;
  PlannerView view() const override;
  std::map<std::string, std::string> derivedParameters() const override;

  const std::vector<SvppObstacle>& obstacles() const { return obstacles_; }
  const SvppTrace& trace() const { return trace_; }
  const SvppOptions& options() const { return options_; }

 protected:
  void buildRoadmap(std::uint64_t seed, const Termination& stop, PlanResult& result) override;
  void answer(const cspace::Query& query, std::uint64_t seed, const Termination& stop,
              PlanResult& result) override;

 private:
  SvppTrial tryPattern(const cspace::Query& query, const Pattern& pattern, double best_length,
                       const Termination& stop, PhaseTimes& times);
  bool validPath(const std::vector<Eigen::VectorXd>& path) const;

  SvppOptions options_;
  std::vector<SvppObstacle> obstacles_;
  SvppTrace trace_;
  ObstacleSamples chosen_samples_;  // the returned pattern's samples (class 1 / 2), for pictures
  std::optional<RiskFunction> chosen_;  // its SVM
  // The patterns' SVMs train one after another: a cache's memory freed by one solve went back to the
  // system and was faulted in again by the next (a third of svpp's time in 3-D).
  svm::SolverWorkspace workspace_;
};

}  // namespace svmp::planners
