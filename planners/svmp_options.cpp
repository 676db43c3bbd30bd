// SVMP's options: read from a scenario's `planners.svmp` (and --set), checked, and the values left
// to the problem derived from it (planners/svmp_planner.hpp, SvmpOptions).
#include "planners/svmp_planner.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace svmp::planners {

constexpr double kMinSigma = 1e-9;  // sigma and fk_sigma: below it the kernel's gamma leaves the doubles

SvmpOptions SvmpOptions::fromParameters(const cspace::ParameterSet& params) {
  SvmpOptions o;
  o.sigma = params.getDouble("sigma", o.sigma, kMinSigma, 1e6);
  o.C = params.getDouble("C", o.C, 1e-9, 1e12);
  o.step = params.getDouble("step", o.step, 1e-9, 1e6);
  o.samples_per_tree = static_cast<int>(params.getInt("samples_per_tree", o.samples_per_tree, 1, 100000));
  o.k = static_cast<int>(params.getInt("k", o.k, 1, 10000));
  o.lazy = params.getBool("lazy", o.lazy);
  o.eps = params.getDouble("eps", o.eps, 1e-15, 1);
  o.cache_mb = params.getDouble("cache_mb", o.cache_mb, 1, 1e6);
  o.truncated = params.getBool("truncated", o.truncated);
  o.descent_tolerance = params.getDouble("descent_tolerance", o.descent_tolerance, 0, 1e6);
  o.descent_step = params.getDouble("descent_step", o.descent_step, 1e-12, 1e6);
  o.descent_iterations = static_cast<int>(params.getInt("descent_iterations", o.descent_iterations, 1, 1000000));
  o.duplicate_radius = params.getDouble("duplicate_radius", o.duplicate_radius, 0, 1e6);
  o.repair_rounds = static_cast<int>(params.getInt("repair_rounds", o.repair_rounds, 0, 1000));
  o.repair_samples = static_cast<int>(params.getInt("repair_samples", o.repair_samples, 2, 1000000));
  o.repair_trees = params.getBool("repair_trees", o.repair_trees);
  o.lazy_trees = static_cast<int>(params.getInt("lazy_trees", o.lazy_trees, 0, 1000000));
  o.tree_range = params.getDouble("tree_range", o.tree_range, 1e-9, 1e6);
  o.trees_before_build = static_cast<int>(params.getInt("trees_before_build", o.trees_before_build, 0, 1000000));
  o.interior_fraction = params.getDouble("interior_fraction", o.interior_fraction, 0, 1);
  o.tree_expansions_per_node =
      static_cast<int>(params.getInt("tree_expansions_per_node", o.tree_expansions_per_node, 0, 1000000));
  o.centre_in_passage = params.getBool("centre_in_passage", o.centre_in_passage);
  o.defer_centring = params.getBool("defer_centring", o.defer_centring);
  o.sample_self_collision = params.getBool("sample_self_collision", o.sample_self_collision);
  o.kernel = params.getString("kernel", o.kernel, {"rbf", "fk"});
  o.classes = params.getString("classes", o.classes, {"auto", "obstacle", "colour"});
  o.training = params.getString("training", o.training, {"auto", "full", "neighbourhood"});
  o.fk_sigma = params.getDouble("fk_sigma", o.fk_sigma, -1, 1e6);
  if (o.fk_sigma > 0 && o.fk_sigma < kMinSigma)  // 1e-300 gave the kernel an infinite gamma
    throw cspace::ScenarioError(params.describe("fk_sigma") + ": " + cspace::parameterText(o.fk_sigma) +
                                " is neither <= 0 (derived from the robot's reach) nor at least 1e-09");
  return o;
}

std::string SvmpOptions::validate() const {
  auto positiveOrDerived = [](double v) { return v == kDerived || (v > 0 && std::isfinite(v)); };
  if (!positiveOrDerived(sigma)) return "sigma must be positive, got " + std::to_string(sigma);
  if (!(C > 0) || !std::isfinite(C)) return "C must be positive, got " + std::to_string(C);
  if (!positiveOrDerived(step)) return "step must be positive, got " + std::to_string(step);
  if ((samples_per_tree < 1 && samples_per_tree != kDerived) || k < 1 || descent_iterations < 1 ||
      repair_samples < 2 || repair_rounds < 0 || lazy_trees < 0 || tree_expansions_per_node < 0 ||
      trees_before_build < 0)
    return "counts must be positive (samples_per_tree, k, descent_iterations >= 1, repair_samples >= 2, "
           "repair_rounds, lazy_trees, tree_expansions_per_node and trees_before_build >= 0)";
  if (!positiveOrDerived(tree_range)) return "tree_range must be positive, got " + std::to_string(tree_range);
  if (!(eps > 0) || !(cache_mb > 0)) return "eps and cache_mb must be positive";
  if (kernel != "rbf" && kernel != "fk") return "kernel must be rbf or fk, got " + kernel;
  if (classes != "auto" && classes != "obstacle" && classes != "colour")
    return "classes must be auto, obstacle or colour, got " + classes;
  if (training != "auto" && training != "full" && training != "neighbourhood")
    return "training must be auto, full or neighbourhood, got " + training;
  if (!std::isfinite(fk_sigma) || (fk_sigma > 0 && fk_sigma < kMinSigma))
    return "fk_sigma must be finite, and <= 0 (derived) or at least 1e-09, got " + cspace::parameterText(fk_sigma);
  if (!(interior_fraction >= 0 && interior_fraction <= 1))
    return "interior_fraction must be in [0, 1], got " + std::to_string(interior_fraction);
  return "";
}

SvmpOptions SvmpOptions::resolvedFor(const cspace::ConfigurationSpace& space, int trees) const {
  SvmpOptions o = *this;
  if (o.samples_per_tree == kDerived) {
    const int spread = kSampleBudget / std::max(trees, 1);
    o.samples_per_tree = std::clamp(spread, kMinSamplesPerTree, kSamplesPerTree);
  }
  if (o.step == kDerived)
    o.step = (space.upper() - space.lower()).cwiseProduct(space.metricScale()).mean() / 40;
  if (o.sigma == kDerived) o.sigma = 2 * o.step;
  if (o.tree_range == kDerived) o.tree_range = 0.2 * space.distance(space.lower(), space.upper());
  return o;
}

DescentOptions SvmpOptions::descent() const {
  DescentOptions d;
  d.tolerance = descent_tolerance;
  d.max_step = descent_step > 0 ? descent_step : sigma;
  d.max_iterations = descent_iterations;
  return d;
}

}  // namespace svmp::planners
