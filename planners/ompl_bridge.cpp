#include "planners/ompl_bridge.hpp"

#include <ompl/base/MotionValidator.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/StateValidityChecker.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/planners/prm/LazyPRM.h>
#include <ompl/geometric/planners/prm/PRM.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/util/Console.h>

#include <chrono>
#include <random>

namespace svmp::planners {
namespace {

namespace ob = ompl::base;
namespace og = ompl::geometric;

Eigen::VectorXd toConfiguration(const ob::State* s, const Eigen::VectorXd& scale) {
  const auto* v = s->as<ob::RealVectorStateSpace::StateType>();
  Eigen::VectorXd q(scale.size());
  for (int i = 0; i < q.size(); ++i) q[i] = v->values[i] / scale[i];
  return q;
}

class ValidityChecker final : public ob::StateValidityChecker {
 public:
  ValidityChecker(const ob::SpaceInformationPtr& si, const PlanningContext& c)
      : ob::StateValidityChecker(si), context_(c) {}
  bool isValid(const ob::State* s) const override {
    return context_.checker.isValid(toConfiguration(s, context_.space.metricScale()));
  }

 private:
  const PlanningContext& context_;
};

class SegmentValidator final : public ob::MotionValidator {
 public:
  SegmentValidator(const ob::SpaceInformationPtr& si, const PlanningContext& c)
      : ob::MotionValidator(si), context_(c) {}
  // OMPL's contract: s1 is valid; s2 and the interior are checked.
  bool checkMotion(const ob::State* s1, const ob::State* s2) const override {
    const Eigen::VectorXd& scale = context_.space.metricScale();
    const bool ok = context_.validator.isValidIncludingEnd(toConfiguration(s1, scale),
                                                           toConfiguration(s2, scale));
    ok ? ++valid_ : ++invalid_;
    return ok;
  }
  bool checkMotion(const ob::State* s1, const ob::State* s2,
                   std::pair<ob::State*, double>& last_valid) const override {
    // Walks from s1 so that the last valid configuration is known (RRT-style extension).
    const Eigen::VectorXd& scale = context_.space.metricScale();
    const Eigen::VectorXd a = toConfiguration(s1, scale), b = toConfiguration(s2, scale);
    const int segments = context_.validator.interiorPoints(context_.space.distance(a, b)) + 1;
    Eigen::VectorXd q(a.size());
    for (int i = 1; i <= segments; ++i) {
      context_.space.interpolate(a, b, static_cast<double>(i) / segments, q);
      if (!context_.checker.isValid(q)) {
        last_valid.second = static_cast<double>(i - 1) / segments;
        if (last_valid.first) si_->getStateSpace()->interpolate(s1, s2, last_valid.second, last_valid.first);
        ++invalid_;
        return false;
      }
    }
    ++valid_;
    return true;
  }

 private:
  const PlanningContext& context_;
};

// Uniform sampling from our seeded generator, so OMPL's samples follow the run's seed.
class SeededSampler final : public ob::StateSampler {
 public:
  SeededSampler(const ob::StateSpace* space, std::uint64_t seed) : ob::StateSampler(space), rng_(seed) {}
  void sampleUniform(ob::State* state) override {
    const auto& bounds = space_->as<ob::RealVectorStateSpace>()->getBounds();
    auto* v = state->as<ob::RealVectorStateSpace::StateType>();
    for (size_t i = 0; i < bounds.low.size(); ++i)
      v->values[i] = std::uniform_real_distribution<double>(bounds.low[i], bounds.high[i])(rng_);
  }
  void sampleUniformNear(ob::State* state, const ob::State* near, double distance) override {
    const auto& bounds = space_->as<ob::RealVectorStateSpace>()->getBounds();
    auto* v = state->as<ob::RealVectorStateSpace::StateType>();
    const auto* c = near->as<ob::RealVectorStateSpace::StateType>();
    for (size_t i = 0; i < bounds.low.size(); ++i)
      v->values[i] = std::clamp(c->values[i] + std::uniform_real_distribution<double>(-distance, distance)(rng_),
                                bounds.low[i], bounds.high[i]);
  }
  void sampleGaussian(ob::State* state, const ob::State* mean, double stddev) override {
    const auto& bounds = space_->as<ob::RealVectorStateSpace>()->getBounds();
    auto* v = state->as<ob::RealVectorStateSpace::StateType>();
    const auto* c = mean->as<ob::RealVectorStateSpace::StateType>();
    for (size_t i = 0; i < bounds.low.size(); ++i)
      v->values[i] = std::clamp(c->values[i] + std::normal_distribution<double>(0, stddev)(rng_),
                                bounds.low[i], bounds.high[i]);
  }

 private:
  std::mt19937_64 rng_;
};

class OmplPlanner final : public Planner {
 public:
  OmplPlanner(std::string name, const PlanningContext& context, double time_limit, double range, int k)
      : name_(std::move(name)), context_(context), time_limit_(time_limit), range_(range), k_(k) {}
  std::string name() const override { return name_; }
  void clear() override {}

  PlanResult solve(const cspace::Query& query, std::uint64_t seed) override {
    const auto checks0 = context_.checker.collisionChecks();
    const auto calls0 = context_.validator.calls();
    PlanResult result;
    if (checkEndpoints(context_, query, result)) run(query, seed, result);
    result.collision_checks = context_.checker.collisionChecks() - checks0;
    result.local_planner_calls = context_.validator.calls() - calls0;
    return result;
  }

 private:
  void run(const cspace::Query& query, std::uint64_t seed, PlanResult& result) {
    ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
    const Eigen::VectorXd& scale = context_.space.metricScale();
    const int dim = context_.space.dim();
    auto space = std::make_shared<ob::RealVectorStateSpace>(dim);
    ob::RealVectorBounds bounds(dim);
    for (int i = 0; i < dim; ++i) {
      bounds.setLow(i, context_.space.lower()[i] * scale[i]);
      bounds.setHigh(i, context_.space.upper()[i] * scale[i]);
    }
    space->setBounds(bounds);
    std::uint64_t sampler_seed = seed;
    space->setStateSamplerAllocator([sampler_seed](const ob::StateSpace* s) mutable {
      return std::make_shared<SeededSampler>(s, sampler_seed++ * 0x9E3779B97F4A7C15ULL + 1);
    });
    auto si = std::make_shared<ob::SpaceInformation>(space);
    si->setStateValidityChecker(std::make_shared<ValidityChecker>(si, context_));
    si->setMotionValidator(std::make_shared<SegmentValidator>(si, context_));
    si->setup();
    auto pdef = std::make_shared<ob::ProblemDefinition>(si);
    ob::ScopedState<> start(space), goal(space);
    for (int i = 0; i < dim; ++i) {
      start[i] = query.start[i] * scale[i];
      goal[i] = query.goal[i] * scale[i];
    }
    pdef->setStartAndGoalStates(start, goal);
    ob::PlannerPtr planner;
    if (name_ == "ompl-prm") {
      auto prm = std::make_shared<og::PRM>(si);
      if (k_ > 0) prm->setMaxNearestNeighbors(k_);
      planner = prm;
    } else if (name_ == "ompl-lazyprm") {
      planner = std::make_shared<og::LazyPRM>(si);
    } else {
      auto rrt = std::make_shared<og::RRTConnect>(si);
      if (range_ > 0) rrt->setRange(range_);
      planner = rrt;
    }
    planner->setProblemDefinition(pdef);
    planner->setup();
    const auto t0 = Clock::now();
    const ob::PlannerStatus status = planner->solve(time_limit_);
    result.times.query_ms = msSince(t0);
    ob::PlannerData data(si);
    planner->getPlannerData(data);
    result.milestones = data.numVertices();
    result.roadmap_edges = data.numEdges();
    if (status == ob::PlannerStatus::EXACT_SOLUTION) {
      auto* path = pdef->getSolutionPath()->as<og::PathGeometric>();
      for (size_t i = 0; i < path->getStateCount(); ++i)
        result.path.push_back(toConfiguration(path->getState(i), scale));
      result.status = PlanStatus::kSolved;
    } else {
      result.status = status == ob::PlannerStatus::TIMEOUT || status == ob::PlannerStatus::APPROXIMATE_SOLUTION
                          ? PlanStatus::kTimeout
                          : PlanStatus::kFailed;
      result.message = std::string("OMPL: ") + status.asString();
    }
  }

  std::string name_;
  PlanningContext context_;
  double time_limit_, range_;
  int k_;
};

}  // namespace

std::unique_ptr<Planner> makeOmplPlanner(const std::string& name, const PlanningContext& context,
                                         const cspace::ParameterSet& params) {
  if (name != "ompl-prm" && name != "ompl-lazyprm" && name != "ompl-rrtconnect")
    throw cspace::ScenarioError("unknown OMPL planner '" + name + "'");
  const double time_limit = params.getDouble("time_limit", 10.0, 1e-3, 1e6);
  const double range = params.getDouble("range", 0.0, 0.0);
  const int k = static_cast<int>(params.getInt("k", 0, 0, 10000));
  return std::make_unique<OmplPlanner>(name, context, time_limit, range, k);
}

}  // namespace svmp::planners
