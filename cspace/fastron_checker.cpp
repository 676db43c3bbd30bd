#include "cspace/fastron_checker.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>
#include <stdexcept>

#include "cspace/parallel_for.hpp"

namespace svmp::cspace {
namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

int featureDimOf(const robots::Robot& robot, FastronFeatures f) {
  return f == FastronFeatures::kJoints ? robot.dof() : 3 * robot.numControlPoints();
}

}  // namespace

FastronCheckerOptions FastronCheckerOptions::defaults(FastronFeatures features) {
  FastronCheckerOptions o;
  o.features = features;
  // docs/fastron.md, "Parameters": the grid search on the Panda.
  if (features == FastronFeatures::kControlPoints) {
    o.model.gamma = 100;
    o.model.beta = 30;
  } else {
    o.model.gamma = 20;
    o.model.beta = 30;
  }
  return o;
}

bool isFastronCheckerName(const std::string& name) { return name == "fastron-fk" || name == "fastron-rbf"; }

FastronCheckerOptions FastronCheckerOptions::fromParameters(const std::string& name, const ParameterSet& params) {
  if (!isFastronCheckerName(name)) throw ScenarioError("unknown checker '" + name + "' (fcl, fastron-fk, fastron-rbf)");
  FastronCheckerOptions o =
      defaults(name == "fastron-fk" ? FastronFeatures::kControlPoints : FastronFeatures::kJoints);
  o.model.gamma = params.getDouble("gamma", o.model.gamma, 1e-9, 1e9);
  o.model.beta = params.getDouble("beta", o.model.beta, 1e-9, 1e9);
  o.model.max_updates = static_cast<int>(params.getInt("max_updates", o.model.max_updates, 1, 100000000));
  o.model.max_support = static_cast<int>(params.getInt("max_support", o.model.max_support, 1, 10000000));
  o.initial_samples = static_cast<int>(params.getInt("initial_samples", o.initial_samples, 1, 1000000));
  o.exploit_samples = static_cast<int>(params.getInt("exploit_samples", o.exploit_samples, 0, 10000000));
  o.exploit_sigma = params.getDouble("exploit_sigma", o.exploit_sigma, 1e-9, 10);
  o.explore_samples = static_cast<int>(params.getInt("explore_samples", o.explore_samples, 0, 10000000));
  return o;
}

std::string FastronCheckerOptions::validate() const {
  if (std::string why = model.validate(); !why.empty()) return why;
  if (initial_samples < 1) return "initial_samples must be at least 1, got " + std::to_string(initial_samples);
  if (exploit_samples < 0 || explore_samples < 0) return "exploit_samples and explore_samples must not be negative";
  if (!(exploit_sigma > 0) || !std::isfinite(exploit_sigma))
    return "exploit_sigma must be positive, got " + std::to_string(exploit_sigma);
  if (threads < 1) return "threads must be at least 1, got " + std::to_string(threads);
  return "";
}

FastronChecker::FastronChecker(std::shared_ptr<const robots::Robot> robot, FastronCheckerOptions options)
    : robot_(std::move(robot)),
      options_(options),
      dim_(featureDimOf(*robot_, options.features)),
      model_(dim_, options.features == FastronFeatures::kJoints ? dim_ : 3, options.model) {
  if (const std::string why = options_.validate(); !why.empty())
    throw std::invalid_argument("Fastron checker: " + why);
  centre_ = (robot_->lowerLimits() + robot_->upperLimits()) / 2;
  half_range_ = (robot_->upperLimits() - robot_->lowerLimits()) / 2;
}

void FastronChecker::features(const Eigen::Ref<const Eigen::VectorXd>& q, float* out) const {
  if (options_.features == FastronFeatures::kJoints) {
    for (int i = 0; i < dim_; ++i) out[i] = static_cast<float>((q[i] - centre_[i]) / half_range_[i]);
    return;
  }
  thread_local Eigen::Matrix3Xd points;
  robot_->controlPoints(q, points);
  for (int i = 0; i < dim_; ++i) out[i] = static_cast<float>(points.data()[i]);
}

const Environment& FastronChecker::environment() const {
  if (!exact_) throw std::logic_error("Fastron checker: used before train()");
  return exact_->environment();
}

double FastronChecker::value(const Eigen::Ref<const Eigen::VectorXd>& q) const {
  thread_local std::vector<float> f;
  f.resize(dim_);
  features(q, f.data());
  return model_.value(f.data());
}

int FastronChecker::check(const Eigen::Ref<const Eigen::VectorXd>& q) const {
  queries_.fetch_add(1, std::memory_order_relaxed);
  if (!robot_->withinLimits(q)) return kJointLimitHit;
  return value(q) > 0 ? kPredictedHit : kFree;
}

void FastronChecker::checkBatch(const Eigen::Ref<const Eigen::MatrixXd>& qs, std::vector<int>& out) const {
  out.resize(qs.cols());
  for (Eigen::Index b = 0; b < qs.cols(); ++b) out[b] = check(qs.col(b));
}

bool FastronChecker::hits(const Eigen::Ref<const Eigen::VectorXd>& q, int id) const {
  if (!exact_) throw std::logic_error("Fastron checker: used before train()");
  return exact_->hits(q, id);
}

double FastronChecker::clearance(const Eigen::Ref<const Eigen::VectorXd>& q) const {
  if (!exact_) throw std::logic_error("Fastron checker: used before train()");
  return exact_->clearance(q);
}

bool FastronChecker::checksSelfCollision() const { return exact_ && exact_->checksSelfCollision(); }

FastronLearnStats FastronChecker::learn(const ValidityChecker& exact, std::vector<Eigen::VectorXd> qs,
                                        std::vector<double> alpha, const std::function<bool()>& stop) {
  exact_ = &exact;
  FastronLearnStats stats;
  const int n = static_cast<int>(qs.size());
  std::vector<std::int8_t> labels(n);
  std::vector<float> feats(static_cast<size_t>(n) * dim_);
  auto t0 = Clock::now();
  parallelFor(n, options_.threads, 64, [&](int i) { labels[i] = exact.check(qs[i]) == kFree ? -1 : 1; });
  stats.label_ms = msSince(t0);
  stats.labelled = n;
  t0 = Clock::now();
  for (int i = 0; i < n; ++i) features(qs[i], &feats[static_cast<size_t>(i) * dim_]);
  stats.train = model_.train(feats, labels, alpha, stop);
  support_q_.clear();
  support_alpha_.clear();
  support_label_.clear();
  for (int i : model_.supportIndices()) {
    support_q_.push_back(std::move(qs[i]));
    support_alpha_.push_back(alpha[i]);
    support_label_.push_back(labels[i]);
  }
  stats.learn_ms = msSince(t0);
  return stats;
}

FastronLearnStats FastronChecker::train(const ValidityChecker& exact, std::uint64_t seed,
                                        const std::vector<Eigen::VectorXd>& extra,
                                        const std::function<bool()>& stop) {
  Rng rng(seed);
  std::vector<Eigen::VectorXd> qs;
  const Eigen::VectorXd lo = robot_->lowerLimits(), hi = robot_->upperLimits();
  for (int i = 0; i < options_.initial_samples; ++i) {
    Eigen::VectorXd q(lo.size());
    for (int k = 0; k < q.size(); ++k) q[k] = std::uniform_real_distribution<double>(lo[k], hi[k])(rng);
    qs.push_back(std::move(q));
  }
  for (const auto& q : extra) robot_->checkConfiguration(q, "Fastron training point"), qs.push_back(q);
  std::vector<double> alpha(qs.size(), 0.0);
  return learn(exact, std::move(qs), std::move(alpha), stop);
}

FastronLearnStats FastronChecker::update(const ValidityChecker& exact, std::uint64_t seed,
                                         const std::vector<Eigen::VectorXd>& extra) {
  Rng rng(seed);
  std::vector<Eigen::VectorXd> qs = support_q_;
  std::vector<double> alpha = support_alpha_;
  const Eigen::VectorXd lo = robot_->lowerLimits(), hi = robot_->upperLimits();
  // Stage 1, exploitation: the C-obstacles moved a little; look near the boundary the model knows,
  // around the support points in collision (the rarer class, whose misses cost the TPR).
  std::vector<int> around;
  for (size_t i = 0; i < support_q_.size(); ++i)
    if (support_label_[i] > 0) around.push_back(static_cast<int>(i));
  if (around.empty())
    for (size_t i = 0; i < support_q_.size(); ++i) around.push_back(static_cast<int>(i));
  const int support = static_cast<int>(around.size());
  // More of them than samples: a random subset. In storage order the newest support points, those
  // nearest the moved obstacle, come last, and a prefix would never perturb them (Fastron RBF keeps
  // 2-3k support points against 1,000 samples).
  if (support > options_.exploit_samples)
    for (int i = 0; i < options_.exploit_samples; ++i)
      std::swap(around[i], around[i + std::uniform_int_distribution<int>(0, support - 1 - i)(rng)]);
  for (int i = 0; support > 0 && i < options_.exploit_samples; ++i) {
    Eigen::VectorXd q = support_q_[around[i % support]];
    for (int k = 0; k < q.size(); ++k)
      q[k] = std::clamp(q[k] + std::normal_distribution<double>(0, options_.exploit_sigma * (hi[k] - lo[k]))(rng),
                        lo[k], hi[k]);
    qs.push_back(std::move(q));
  }
  // Stage 2, exploration: obstacles that entered where the model knows nothing.
  for (int i = 0; i < options_.explore_samples; ++i) {
    Eigen::VectorXd q(lo.size());
    for (int k = 0; k < q.size(); ++k) q[k] = std::uniform_real_distribution<double>(lo[k], hi[k])(rng);
    qs.push_back(std::move(q));
  }
  for (const auto& q : extra) robot_->checkConfiguration(q, "Fastron training point"), qs.push_back(q);
  alpha.resize(qs.size(), 0.0);
  return learn(exact, std::move(qs), std::move(alpha), {});
}

}  // namespace svmp::cspace
