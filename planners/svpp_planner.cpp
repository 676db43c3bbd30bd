#include "planners/svpp_planner.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <set>
#include <sstream>

#include "planners/planner_registry.hpp"
#include "robots/point_robot.hpp"

namespace svmp::planners {

SvppOptions SvppOptions::fromParameters(const cspace::ParameterSet& params) {
  SvppOptions o;
  o.virtual_samples = static_cast<int>(params.getInt("virtual_samples", o.virtual_samples, 1, 100));
  o.virtual_distance = params.getDouble("virtual_distance", o.virtual_distance, 1e-9, 1e6);
  o.guide_distance = params.getDouble("guide_distance", o.guide_distance, 1e-9, 1e6);
  o.guide_spacing = params.getDouble("guide_spacing", o.guide_spacing, 1e-6, 1e6);
  o.patterns = static_cast<int>(params.getInt("patterns", o.patterns, 0, 100000));
  o.max_patterns = static_cast<int>(params.getInt("max_patterns", o.max_patterns, 1, 100000));
  o.search_angle_deg = params.getDouble("search_angle_deg", o.search_angle_deg, 1, 359);
  o.step = params.getDouble("step", o.step, 1e-9, 1e6);
  o.max_steps = static_cast<int>(params.getInt("max_steps", o.max_steps, 0, 10000000));
  o.gamma = params.getDouble("gamma", o.gamma, 1e-12, 1e12);
  o.C = params.getDouble("C", o.C, 1e-9, 1e12);
  o.eps = params.getDouble("eps", o.eps, 1e-15, 1);
  return o;
}

void SvppOptions::requireKeysFor(const cspace::ParameterSet& params, int dim) {
  if (dim != 2 && params.has("search_angle_deg"))
    throw cspace::ScenarioError(params.describe("search_angle_deg") +
                                ": applies in 2-D only; in 3-D the path follows a plane fitted to the surface "
                                "(Miura sec. IV-B-4)");
}

std::string SvppOptions::validate() const {
  auto positiveOrDerived = [](double v) { return v == kDerived || (v > 0 && std::isfinite(v)); };
  std::ostringstream why;
  if (virtual_samples < 1)
    why << "virtual_samples must be >= 1, got " << virtual_samples;
  else if (!(positiveOrDerived(virtual_distance) && positiveOrDerived(guide_distance) &&
             positiveOrDerived(guide_spacing) && positiveOrDerived(step)))
    why << "virtual_distance, guide_distance, guide_spacing and step must be positive";
  else if (virtual_distance != kDerived && guide_distance != kDerived &&
           !(guide_distance > virtual_distance))
    why << "guide_distance (" << guide_distance << ") must exceed virtual_distance ("
        << virtual_distance << "): the guides wrap the virtual obstacles";
  else if (patterns < 0 || max_patterns < 1 || max_steps < 0)
    why << "patterns and max_steps must be >= 0, max_patterns >= 1";
  else if (patterns > max_patterns)
    why << "patterns (" << patterns << ") must not exceed max_patterns (" << max_patterns << ")";
  else if (!(search_angle_deg > 0 && search_angle_deg < 360))
    why << "search_angle_deg must lie in (0, 360), got " << search_angle_deg;
  else if (!(positiveOrDerived(gamma) && C > 0 && eps > 0) || !std::isfinite(C))
    why << "gamma, C and eps must be positive and finite";
  return why.str();
}

namespace {

// Guides every d_p on both sides of a line at most the diagonal long, and in 3-D across a plane's
// width.
double guideSampleBound(const cspace::ConfigurationSpace& space, double spacing, double distance) {
  const double diagonal = (space.upper() - space.lower()).norm();
  const double across = space.dim() == 3 ? (diagonal + 2 * distance) / spacing + 2 : 1;
  return 2 * (diagonal / spacing + 2) * across;
}

// How the patterns tried ended, counted ("left the space: 3, stopped at max_steps (542): 1"): a user
// reads which limit to raise.
std::string howThePatternsEnded(const std::vector<SvppTrial>& trials, int max_steps) {
  std::map<std::string, int> reasons;
  for (const SvppTrial& t : trials)
    ++reasons[t.follow.reached() ? (t.valid ? "reached the goal but not certified"
                                            : "reached the goal through an obstacle")
              : t.follow.status == FollowStatus::kStepLimit
                  ? "stopped at max_steps (" + std::to_string(max_steps) + ")"
                  : followStatusName(t.follow.status)];
  std::ostringstream out;
  for (auto it = reasons.begin(); it != reasons.end(); ++it)
    out << (it == reasons.begin() ? "" : ", ") << it->first << ": " << it->second;
  return out.str();
}

}  // namespace

std::string SvppOptions::validateFor(const cspace::ConfigurationSpace& space) const {
  if (std::string why = validate(); !why.empty()) return why;
  const double diagonal = (space.upper() - space.lower()).norm();
  const double guides = guideSampleBound(space, guide_spacing, guide_distance);
  const double virtuals = 4 * std::pow(virtual_samples, space.dim() - 1);
  std::ostringstream why;
  if (diagonal / step > kMaxStepsPerDiagonal)
    why << "step (" << step << ") is below 1/" << kMaxStepsPerDiagonal << " of the space's diagonal ("
        << diagonal << ")";
  else if (virtuals > kMaxVirtualSamples)
    why << "virtual_samples (" << virtual_samples << ") gives " << virtuals << " virtual samples in "
        << space.dim() << "-D (4 N_v^" << space.dim() - 1 << "), more than " << kMaxVirtualSamples;
  else if (guides > kMaxGuideSamples)
    why << "guide_spacing (" << guide_spacing << ") gives up to " << guides
        << " guide samples in this space, more than " << kMaxGuideSamples;
  return why.str();
}

SvppOptions SvppOptions::resolvedFor(const cspace::ConfigurationSpace& space, int obstacles) const {
  const Eigen::VectorXd sides = space.upper() - space.lower();
  const int dim = space.dim();
  const double spacing = std::pow(sides.prod() / std::max(obstacles, 1), 1.0 / dim);
  const double s = std::min(sides.mean() / kPaperSide,
                            spacing / (dim == 2 ? kPaperSpacing2d : kPaperSpacing3d));
  SvppOptions o = *this;
  for (auto [value, paper] : {std::pair{&o.virtual_distance, kPaperVirtualDistance},
                              {&o.guide_distance, kPaperGuideDistance},
                              {&o.guide_spacing, kPaperGuideSpacing},
                              {&o.step, kPaperStep}})
    if (*value == kDerived) *value = paper * s;
  if (o.gamma == kDerived) o.gamma = kPaperGamma / (s * s);
  // A dense 3-D field (over about 2,000 obstacles in a cube) spaces its guides wider rather than be
  // refused.
  if (guide_spacing == kDerived)
    while (guideSampleBound(space, o.guide_spacing, o.guide_distance) > kMaxGuideSamples) o.guide_spacing *= 1.1;
  if (step == kDerived)  // twice the finest step a file may set, so rounding never refuses it
    o.step = std::max(o.step, 2 * (space.upper() - space.lower()).norm() / kMaxStepsPerDiagonal);
  return o;
}

SampleLayout SvppOptions::layout() const {
  return {virtual_samples, virtual_distance, guide_distance, guide_spacing};
}

SurfaceFollowing SvppOptions::following(const cspace::Query& query, const Eigen::VectorXd& lower,
                                        const Eigen::VectorXd& upper) const {
  SurfaceFollowing f;
  f.step = step;
  f.search_angle = search_angle_deg * std::numbers::pi / 180;
  const double automatic = std::ceil(3 * (query.goal - query.start).norm() / step);
  f.max_steps = max_steps > 0 ? max_steps : static_cast<int>(std::min(automatic, 1e7));
  f.lower = lower;
  f.upper = upper;
  return f;
}

svm::BinaryModel trainSvppModel(const TrainingSet& set, double gamma, double C, double eps,
                                svm::SolverWorkspace* workspace, const std::function<bool()>& stop) {
  svm::SolverOptions solver;
  solver.eps = eps;
  solver.stop = stop;
  const svm::Kernel kernel = svm::Kernel::rbf(gamma);
  const svm::SolverResult solution = svm::solveBinary(set.X, set.y, Eigen::VectorXd::Constant(set.size(), C),
                                                      kernel, solver, nullptr, workspace);
  return svm::BinaryModel::fromSolution(set.X, set.y, solution, kernel);
}

SVMP_REGISTER_PLANNER("svpp",
                      [](const PlanningContext& context, const cspace::ParameterSet& params) {
                        SvppOptions::requireKeysFor(params, context.space.dim());
                        const SvppOptions o =
                            SvppOptions::fromParameters(params).resolvedFor(
                                context.space, context.checker.environment().numReal());
                        if (const std::string why = o.validateFor(context.space); !why.empty()) {
                          // Blame a parameter the message names and the user set (file or --set):
                          // `guide_distance must exceed virtual_distance` after --set virtual_distance
                          // is about the flag, not the file's unset guide_distance.
                          std::string key;
                          for (const auto& [name, declaration] : params.declarations())
                            if (params.has(name) && why.find(name) != std::string::npos &&
                                (key.empty() || why.find(name) < why.find(key)))
                              key = name;
                          throw cspace::ScenarioError(!key.empty() ? params.describe(key) + ": " + why
                                                                   : "planners.svpp: " + why);
                        }
                        return std::make_unique<SvppPlanner>(context, o);
                      });

SvppPlanner::SvppPlanner(const PlanningContext& context, SvppOptions options)
    : Planner(context),
      options_(options.resolvedFor(context.space, context.checker.environment().numReal())) {
  if (const std::string why = options_.validateFor(context.space); !why.empty())
    throw std::invalid_argument("svpp: " + why);
}

void SvppPlanner::clear() {
  forgetBuild();
  obstacles_.clear();
  clearQuery();
}

void SvppPlanner::clearQuery() {
  trace_ = {};
  chosen_samples_ = {};
  chosen_.reset();
}

PlannerView SvppPlanner::view() const {
  PlannerView v;
  if (chosen_) v.samples = &chosen_samples_, v.risk = &*chosen_;
  v.svpp = &trace_;
  return v;
}

std::map<std::string, std::string> SvppPlanner::derivedParameters() const {
  using cspace::parameterText;
  const SvppOptions& o = options_;
  return {{"virtual_distance", parameterText(o.virtual_distance)}, {"guide_distance", parameterText(o.guide_distance)},
          {"guide_spacing", parameterText(o.guide_spacing)},       {"step", parameterText(o.step)},
          {"gamma", parameterText(o.gamma)},
          {"patterns", std::to_string(o.patternsFor(context_.space.dim()))}};
}

void SvppPlanner::buildRoadmap(std::uint64_t, const Termination& stop, PlanResult& result) {
  const auto t0 = Clock::now();
  const auto* point = dynamic_cast<const robots::PointRobot*>(&context_.checker.robot());
  if (!point) {
    result.status = PlanStatus::kInvalidInput;
    result.message = "svpp plans for point robots in 2-D and 3-D only; the robot is '" +
                     context_.checker.robot().name() + "'";
    return;
  }
  obstacles_ = mergeObstacles(obstacleParts(context_.checker.environment(), point->dof(), point->radius()),
                              stop.asFunction());
  result.times.sampling_ms += msSince(t0);
  if (stop()) {
    result.status = PlanStatus::kTimeout;
    result.message = "time limit reached while merging overlapping obstacles";
    return;
  }
  result.status = PlanStatus::kSolved;
}

bool SvppPlanner::validPath(const std::vector<Eigen::VectorXd>& path) const {
  for (size_t i = 0; i + 1 < path.size(); ++i)
    if (!context_.validator.isValidIncludingEnd(path[i], path[i + 1])) return false;
  return true;
}

SvppTrial SvppPlanner::tryPattern(const cspace::Query& query, const Pattern& pattern,
                                  double best_length, const Termination& stop, PhaseTimes& times) {
  SvppTrial trial;
  trial.pattern = pattern;
  auto t0 = Clock::now();
  const auto& space = context_.space;
  trial.samples = patternTrainingSet(trace_.frame, obstacles_, pattern, options_.layout(),
                                     space.lower(), space.upper());
  times.sampling_ms += msSince(t0);
  t0 = Clock::now();
  trial.model = trainSvppModel(trial.samples, options_.gamma, options_.C, options_.eps, &workspace_,
                               stop.asFunction());
  trial.svm_ms = msSince(t0);
  times.training_ms += trial.svm_ms;
  if (stop()) return trial;  // a solve the limit cut short: no model to follow
  t0 = Clock::now();
  SurfaceFollowing following = options_.following(query, space.lower(), space.upper());
  following.max_length = best_length;
  following.stop = stop.asFunction();
  if (space.dim() == 2)
    trial.follow =
        followSurface2d(trial.model, query.start, query.goal, trace_.frame.along, following);
  else
    trial.follow = followSurface3d(
        trial.model, query.start, query.goal, [&](const Eigen::VectorXd&) { return query.goal; },
        following);
  trial.valid = trial.follow.reached() && validPath(trial.follow.path);
  trial.path_ms = msSince(t0);
  times.query_ms += trial.path_ms;
  return trial;
}

void SvppPlanner::answer(const cspace::Query& query, std::uint64_t seed, const Termination& stop,
                         PlanResult& result) {
  if ((query.goal - query.start).norm() < 1e-12) {
    result.status = PlanStatus::kSolved;
    result.path = {query.start, query.goal};
    return;
  }
  const int dim = context_.space.dim();
  trace_.obstacles = obstacles_;
  trace_.frame = dim == 2 ? nominalLine(query.start, query.goal)
                          : nominalPlane(query.start, query.goal, allVertices(obstacles_, dim));

  // Patterns: the initial one, then a random walk flipping one obstacle at a time, new patterns
  // only.
  const int wanted = options_.patternsFor(dim);
  const int obstacles = static_cast<int>(obstacles_.size());
  const double distinct = std::ldexp(1.0, std::min(obstacles, 60));
  cspace::Rng rng(seed ^ 0x5F9D'3C21'7A11'B00BULL);
  std::set<Pattern> tried;
  Pattern pattern = initialPattern(obstacles_, trace_.frame);
  double best_length = std::numeric_limits<double>::infinity();
  const char* ended = "no untried pattern found";  // why the search stopped, for a failure's message
  while (true) {
    if (static_cast<int>(tried.size()) >= options_.max_patterns) {
      ended = "max_patterns";
      break;
    }
    if (static_cast<double>(tried.size()) >= distinct) {
      ended = "every pattern of the merged obstacles";
      break;
    }
    if (stop()) {
      result.status = PlanStatus::kTimeout;
      result.message = "time limit reached after " + std::to_string(tried.size()) + " patterns";
      break;
    }
    tried.insert(pattern);
    trace_.trials.push_back(tryPattern(query, pattern, best_length, stop, result.times));
    if (trace_.trials.back().valid)
      best_length = std::min(best_length, trace_.trials.back().follow.length);
    if (static_cast<int>(tried.size()) >= wanted && std::isfinite(best_length)) {
      ended = "enough patterns gave a path, none certified";
      break;
    }
    if (obstacles == 0) break;
    std::uniform_int_distribution<int> pick(0, obstacles - 1);
    for (int attempt = 0; attempt < 100000 && tried.count(pattern); ++attempt) {
      const int flip = pick(rng);
      pattern[flip] = !pattern[flip];
    }
    if (tried.count(pattern)) {  // 100,000 flips found none untried
      if (static_cast<double>(tried.size()) >= distinct) ended = "every pattern of the merged obstacles";
      break;
    }
  }

  // The shortest valid path that the certifier proves.
  const std::string cut_short = result.status == PlanStatus::kTimeout ? result.message : "";
  std::vector<int> order;
  for (int i = 0; i < static_cast<int>(trace_.trials.size()); ++i)
    if (trace_.trials[i].valid) order.push_back(i);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return trace_.trials[a].follow.length < trace_.trials[b].follow.length;
  });
  for (int i : order) {
    result.status = PlanStatus::kSolved;
    result.message.clear();
    result.path = trace_.trials[i].follow.path;
    certify(result, seed, stop);
    if (result.solved()) {
      trace_.chosen = i;
      break;
    }
  }
  if (trace_.chosen >= 0) {
    if (!cut_short.empty())  // an anytime answer: the patterns left untried might have given a shorter path
      result.warnings.push_back(cut_short + " of the " + std::to_string(wanted) +
                                " wanted: the shortest certified path among them is returned");
    const SvppTrial& chosen = trace_.trials[trace_.chosen];
    result.support_vectors = chosen.model.numSupportVectors();
    chosen_samples_.points = chosen.samples.X;
    for (int i = 0; i < chosen.samples.size(); ++i) {
      chosen_samples_.labels.push_back(chosen.samples.y[i] > 0 ? 1 : 2);
      chosen_samples_.boundary.push_back(chosen.samples.kind[i] != SampleKind::kObstacle);
    }
    chosen_.emplace(std::vector<svm::BinaryModel>{chosen.model}, std::vector<int>{1},
                    Eigen::VectorXd::Ones(dim), false);
    return;
  }
  if (result.status == PlanStatus::kTimeout && result.message != cut_short) return;  // the certifier's own
  // Why each pattern failed, and why no more were tried.
  const int max_steps = options_.following(query, context_.space.lower(), context_.space.upper()).max_steps;
  const std::string tally = howThePatternsEnded(trace_.trials, max_steps);
  if (result.status == PlanStatus::kTimeout || stop()) {
    result.status = PlanStatus::kTimeout;
    result.message = "time limit reached after " + std::to_string(trace_.trials.size()) + " patterns" +
                     (tally.empty() ? "" : " (" + tally + ")");
    result.path.clear();
    return;
  }
  result.status = PlanStatus::kFailed;
  result.message = "no path in " + std::to_string(trace_.trials.size()) + " labelling patterns of " +
                   std::to_string(obstacles) + " merged obstacles (" + ended + "; " + tally + ")";
  result.path.clear();
}

}  // namespace svmp::planners
