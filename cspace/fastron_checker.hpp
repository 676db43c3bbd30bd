#pragma once
// A learned proxy collision checker (Das & Yip 2019): a Fastron model (svm/fastron.hpp) behind the
// ValidityChecker seam, so every planner and the OMPL bridge can plan on it instead of FCL. Two
// feature maps: `fastron-rbf`, the rational quadratic kernel on joints scaled to [-1, 1] (the earlier
// Fastron), and `fastron-fk`, the FK kernel: the same base kernel on the workspace positions of the
// robot's control points (robots/robot.hpp), summed over control points (sec. III-A, eq. 4).
//
// Learning (sec. III-B): train() labels uniform configurations with the exact checker and trains from
// zero; update(), after the workspace changed, runs the two-stage active learning (Gaussian
// perturbations of the support points in collision, the rarer class whose misses cost the TPR (all
// support points when none is; a random subset when there are more than samples), then uniform
// exploration), relabels the support points and the
// new samples with the exact checker and retrains starting from the previous weights. Extra
// configurations (a planner's start and goal) can be added to either; a converged model classifies
// every training point correctly, to rounding (training sums margins in double, queries in float, so a
// point whose margin is within rounding of zero may flip; svmp-plan warns of a start or goal predicted
// in collision).
//
// What the proxy answers: check() is the model's prediction (kPredictedHit when f > 0, limits tested
// exactly); hits(), clearance() and everything per obstacle go to the exact checker of the last
// train/update (which must outlive its use). collisionChecks() counts model queries only.
// Thread safety: const methods may run concurrently (thread-local feature buffers); train() and
// update() may not run beside anything else.
#include <atomic>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "cspace/configuration_space.hpp"
#include "cspace/scenario/parameters.hpp"
#include "cspace/validity_checker.hpp"
#include "svm/fastron.hpp"

namespace svmp::cspace {

enum class FastronFeatures { kJoints, kControlPoints };

struct FastronCheckerOptions {
  FastronFeatures features = FastronFeatures::kControlPoints;
  svm::FastronOptions model;           // gamma, beta, limits (defaults set per feature map below)
  int initial_samples = 5000;          // labelled uniform configurations of the first model
  int exploit_samples = 1000;          // per update: Gaussian perturbations of support points in collision
  double exploit_sigma = 0.1;          // their standard deviation, fraction of each joint's range
  int explore_samples = 200;           // per update: uniform configurations
  int threads = 1;                     // labelling threads

  // The defaults of each feature map (gamma and beta from the grid search in docs/fastron.md).
  static FastronCheckerOptions defaults(FastronFeatures features);
  // `name` is fastron-fk or fastron-rbf; keys: gamma, beta, max_updates, max_support,
  // initial_samples, exploit_samples, exploit_sigma, explore_samples. Throws ScenarioError.
  static FastronCheckerOptions fromParameters(const std::string& name, const ParameterSet& params);
  std::string validate() const;
};

// The checker names `--checker` accepts besides fcl.
bool isFastronCheckerName(const std::string& name);

struct FastronLearnStats {
  double label_ms = 0, learn_ms = 0;  // exact labelling; model training
  int labelled = 0;                   // exact checks made
  svm::FastronTrainStats train;
};

class FastronChecker final : public ValidityChecker {
 public:
  FastronChecker(std::shared_ptr<const robots::Robot> robot, FastronCheckerOptions options);

  // Cold start on options.initial_samples uniform configurations plus `extra`, labelled by `exact`.
  // `stop`, when set, is polled at every update of the model (then train.stopped).
  FastronLearnStats train(const ValidityChecker& exact, std::uint64_t seed,
                          const std::vector<Eigen::VectorXd>& extra = {},
                          const std::function<bool()>& stop = {});
  // Active learning and a warm update after the workspace changed (`exact` sees the new one).
  FastronLearnStats update(const ValidityChecker& exact, std::uint64_t seed,
                           const std::vector<Eigen::VectorXd>& extra = {});

  const robots::Robot& robot() const override { return *robot_; }
  const Environment& environment() const override;
  int check(const Eigen::Ref<const Eigen::VectorXd>& q) const override;
  int checkIncludingVirtual(const Eigen::Ref<const Eigen::VectorXd>& q) const override { return check(q); }
  bool hits(const Eigen::Ref<const Eigen::VectorXd>& q, int id) const override;
  double clearance(const Eigen::Ref<const Eigen::VectorXd>& q) const override;
  bool checksSelfCollision() const override;
  std::uint64_t collisionChecks() const override { return queries_.load(std::memory_order_relaxed); }

  // The model's value f(q) (> 0: predicted in collision); not counted.
  double value(const Eigen::Ref<const Eigen::VectorXd>& q) const;
  // check() for each column of qs (out[i]: kFree, kPredictedHit or kJointLimitHit). One query after
  // another: evaluating several at once (configurations across the vector lanes) measured slower, the
  // support set stays in L1 either way (docs/fastron.md). Counts qs.cols() checks.
  void checkBatch(const Eigen::Ref<const Eigen::MatrixXd>& qs, std::vector<int>& out) const;

  const svm::FastronModel& model() const { return model_; }
  // Configurations of the support points, in the model's storage order.
  const std::vector<Eigen::VectorXd>& supportConfigurations() const { return support_q_; }
  const FastronCheckerOptions& options() const { return options_; }
  int featureDim() const { return dim_; }
  // Writes the features of q (featureDim() floats).
  void features(const Eigen::Ref<const Eigen::VectorXd>& q, float* out) const;

 private:
  FastronLearnStats learn(const ValidityChecker& exact, std::vector<Eigen::VectorXd> qs,
                          std::vector<double> alpha, const std::function<bool()>& stop);

  std::shared_ptr<const robots::Robot> robot_;
  FastronCheckerOptions options_;
  int dim_;
  svm::FastronModel model_;
  const ValidityChecker* exact_ = nullptr;
  std::vector<Eigen::VectorXd> support_q_;
  std::vector<double> support_alpha_;
  std::vector<std::int8_t> support_label_;  // +1 in collision
  Eigen::VectorXd centre_, half_range_;  // joint scaling to [-1, 1]
  mutable std::atomic<std::uint64_t> queries_{0};
};

}  // namespace svmp::cspace
