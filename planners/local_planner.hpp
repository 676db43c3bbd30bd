#pragma once
// The local SVM-based planner of thesis ch. 2: IK-based obstacle samples (ch. 2.2.1), labelled by a
// hyperplane through start and goal (eqs. 2.24-2.25), one binary RBF SVM with per-obstacle C (virtual
// guide obstacles get their lower weight, ch. 2.3), the risk function R(q) = |F(q)| (eq. 2.26, shared
// RiskFunction) and descent on the potential U(q) = mu ||q - q_goal|| + R(q) (eq. 2.27) by fixed-length
// steps along -grad U. No progress towards the goal for `stall_iterations` steps is reported as
// PlanStatus::kLocalMinimum; a step into a real obstacle ends the run as kFailed. Each step is checked
// by the shared motion validator, so the returned path is collision-free at the scenario's resolution.
// Within goal_radius (default sigma) of the goal a collision-free straight motion ends the descent.
// Parameters (scenario `planners.local`): sigma, C, mu, step, boundary_tolerance, goal_radius, eps,
// labelling (balanced|random), link_resolution, obstacle_resolution, boundary_resolution, max_samples,
// max_iterations, stall_iterations. Everything depends on the query: build() learns nothing ahead.
// Thread safety: as every Planner (planners/planner.hpp).
#include <optional>

#include "cspace/scenario/parameters.hpp"
#include "planners/hyperplane_labelling.hpp"
#include "planners/ik_obstacle_sampler.hpp"
#include "planners/planner.hpp"
#include "planners/risk_function.hpp"
#include "svm/solver_workspace.hpp"

namespace svmp::planners {

struct LocalPlannerOptions {
  double sigma = 0.3;
  double C = 100;
  double mu = 0.1;
  double step = 0.02;          // descent step, weighted metric
  double boundary_tolerance = 0.05;  // |F| below which the descent counts as on the boundary
  // Within this distance of the goal (weighted metric) the straight motion to the goal is tried and
  // taken when collision-free; < 0 means sigma. Near the goal the kink of |F| on a decision boundary
  // passing close by is a local minimum of U whenever mu < |grad F| there (the goal itself has
  // U = |F(goal)| > 0 unless it lies on the boundary); the SVM cannot resolve the geometry inside
  // one kernel width anyway. 0 gives the thesis' pure descent (reach the goal only within one step).
  double goal_radius = -1;
  double eps = 1e-3;           // SMO tolerance
  LabellingMethod labelling = LabellingMethod::kBalanced;
  IkSamplingOptions sampling;
  int max_iterations = 20000;
  int stall_iterations = 200;  // steps without a new best distance to the goal

  static LocalPlannerOptions fromParameters(const cspace::ParameterSet& params);
  std::string validate() const;  // "" when usable
  bool operator==(const LocalPlannerOptions&) const = default;
};

class LocalPlanner final : public Planner {
 public:
  LocalPlanner(const PlanningContext& context, LocalPlannerOptions options);
  std::string name() const override { return "local"; }
  bool repairable() const override { return false; }
  void clear() override;
  void clearQuery() override;  // the samples, labels and model belong to one query
  PlannerView view() const override { return {&labelled_, risk(), nullptr}; }
  std::map<std::string, std::string> derivedParameters() const override {
    return {{"goal_radius", cspace::parameterText(options_.goal_radius < 0 ? options_.sigma : options_.goal_radius)}};
  }

  const IkSamples& samples() const { return samples_; }
  const Labelling& labelling() const { return labelling_; }
  const RiskFunction* risk() const { return risk_ ? &*risk_ : nullptr; }

 protected:
  void buildRoadmap(std::uint64_t, const Termination&, PlanResult& result) override {
    result.status = PlanStatus::kSolved;
  }
  void answer(const cspace::Query& query, std::uint64_t seed, const Termination& stop,
              PlanResult& result) override;

 private:
  PlanStatus descend(const cspace::Query& query, const Termination& stop, PlanResult& result) const;

  LocalPlannerOptions options_;
  planners::ObstacleSamples labelled_;  // the samples with their class (1 or 2), for pictures
  IkSamples samples_;
  Labelling labelling_;
  std::optional<RiskFunction> risk_;
  svm::SolverWorkspace workspace_;  // each query's SVM reuses the last one's cache memory
};

}  // namespace svmp::planners
