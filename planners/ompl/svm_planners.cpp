#include "planners/ompl/svm_planners.hpp"

#include <ompl/base/PlannerData.h>
#include <ompl/base/goals/GoalState.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/util/Console.h>

#include <limits>
#include <map>
#include <mutex>
#include <tuple>

#include "planners/ompl/foreign_checker.hpp"
#include "planners/ompl/state_bridge.hpp"
#include "planners/planner_registry.hpp"
#include "planners/roadmap.hpp"

namespace svmp::ompl_planners {
namespace {

namespace og = ::ompl::geometric;
using planners::PlanStatus;

bool isTrue(const std::string& text) { return text == "true" || text == "1"; }

}  // namespace

// A foreign SpaceInformation's checker and validator as our seams.
struct SvmOmplPlannerBase::ForeignSeams {
  explicit ForeignSeams(const ob::SpaceInformationPtr& si)
      : space(configurationSpaceOf(*si)), checker(std::in_place, si), validator(si, *checker, space) {}
  // Our checker with the SpaceInformation's own MotionValidator.
  ForeignSeams(const ob::SpaceInformationPtr& si, const planners::PlanningContext& ours)
      : space(ours.space), validator(si, ours.checker, space) {}
  cspace::ConfigurationSpace space;
  std::optional<ForeignValidityChecker> checker;  // empty when the checker is ours
  ForeignMotionValidator validator;
};

SvmOmplPlannerBase::SvmOmplPlannerBase(const ob::SpaceInformationPtr& si, const std::string& name,
                                       cspace::ParameterSet params, std::string needs_own_checker)
    : ob::Planner(si, name), params_(std::move(params)), needs_own_checker_(std::move(needs_own_checker)) {
  specs_.recognizedGoal = ob::GOAL_STATE;
  specs_.approximateSolutions = name == "local";
  specs_.multithreaded = false;
  specs_.directed = false;
}

SvmOmplPlannerBase::~SvmOmplPlannerBase() = default;

void SvmOmplPlannerBase::declareParameters() {
  readOptions(params_);
  params_.requireAllUsed();
  using Kind = cspace::ParameterDeclaration::Kind;
  for (const auto& [name, declaration] : params_.declarations()) {
    const std::string key = name;
    switch (declaration.kind) {
      case Kind::kDouble:
        params().declareParam<double>(
            key, [this, key](double v) { setParameter(key, cspace::parameterText(v)); },
            [this, key] { return std::stod(currentValue(key)); });
        break;
      case Kind::kInt:
        params().declareParam<long>(
            key, [this, key](long v) { setParameter(key, std::to_string(v)); },
            [this, key] { return std::stol(currentValue(key)); });
        break;
      case Kind::kBool:
        params().declareParam<bool>(
            key, [this, key](bool v) { setParameter(key, v ? "true" : "false"); },
            [this, key] { return isTrue(currentValue(key)); });
        break;
      case Kind::kString:
        params().declareParam<std::string>(
            key, [this, key](std::string v) { setParameter(key, v); }, [this, key] { return currentValue(key); });
        break;
    }
    params()[key].setRangeSuggestion(declaration.range);
  }
}

std::string SvmOmplPlannerBase::currentValue(const std::string& key) const {
  const auto it = params_.values().find(key);
  return it != params_.values().end() ? it->second : params_.declarations().at(key).fallback;
}

// OMPL's ParamSet catches std::invalid_argument: setParam returns false and logs the reason.
void SvmOmplPlannerBase::setParameter(const std::string& key, const std::string& value) {
  cspace::ParameterSet next = params_;
  next.set(key, value, "OMPL parameter of " + getName());
  try {
    readOptions(next);
  } catch (const std::exception& e) {
    throw std::invalid_argument(e.what());
  }
  params_ = std::move(next);
  planner_.reset();  // the next solve builds with the new options
  unusable_.clear();
}

std::string SvmOmplPlannerBase::prepare() {
  planner_.reset();
  context_.reset();
  foreign_.reset();
  const auto* ours = dynamic_cast<const ContextValidityChecker*>(si_->getStateValidityChecker().get());
  own_checker_ = ours != nullptr;
  try {
    if (ours) {
      const planners::PlanningContext& c = ours->context();
      if (dynamic_cast<const ContextMotionValidator*>(si_->getMotionValidator().get())) {
        context_.emplace(c);
      } else {
        foreign_ = std::make_unique<ForeignSeams>(si_, c);
        context_.emplace(planners::PlanningContext{c.space, c.checker, foreign_->validator, c.threads, c.certifier,
                                                   c.repairer});
      }
    } else {
      if (!needs_own_checker_.empty())
        return "the SpaceInformation's StateValidityChecker is not svmp's (svmp::ompl_planners::"
               "ContextValidityChecker, e.g. from ScenarioWorld), and " + needs_own_checker_;
      foreign_ = std::make_unique<ForeignSeams>(si_);
      // A user's checker need not be thread-safe: one thread; no certifier: OMPL's guarantee only.
      context_.emplace(planners::PlanningContext{foreign_->space, *foreign_->checker, foreign_->validator, 1});
    }
    planner_ = planners::makePlanner(getName(), *context_, params_);
  } catch (const std::exception& e) {
    planner_.reset();
    return e.what();
  }
  return "";
}

void SvmOmplPlannerBase::setup() {
  ob::Planner::setup();
  unusable_ = prepare();  // solve() reports it
}

void SvmOmplPlannerBase::clear() {
  ob::Planner::clear();
  if (planner_) planner_->clear();
  last_ = {};
}

ob::PlannerStatus SvmOmplPlannerBase::solve(const ob::PlannerTerminationCondition& ptc) {
  checkValidity();
  last_ = {};
  if (!planner_ && unusable_.empty()) unusable_ = prepare();
  if (!unusable_.empty()) {
    last_.status = PlanStatus::kInvalidInput;
    last_.message = unusable_;
    OMPL_ERROR("%s: %s", getName().c_str(), unusable_.c_str());
    return ob::PlannerStatus::ABORT;
  }
  const auto* goal = dynamic_cast<const ob::GoalState*>(pdef_->getGoal().get());
  if (!goal) {
    OMPL_ERROR("%s: the goal must be a single state (ompl::base::GoalState)", getName().c_str());
    return ob::PlannerStatus::UNRECOGNIZED_GOAL_TYPE;
  }
  if (pdef_->getStartStateCount() == 0) return ob::PlannerStatus::INVALID_START;
  // Beyond the bounds, as OMPL's own planners skip such a start: toConfiguration keeps states within
  // the joint limits, and a path from the limit is not a path from the start given.
  using Check = std::tuple<const ob::State*, const char*, PlanStatus>;
  for (const auto& [state, which, status] : {Check{pdef_->getStartState(0), "start", PlanStatus::kInvalidStart},
                                             Check{goal->getState(), "goal", PlanStatus::kInvalidGoal}})
    if (!si_->satisfiesBounds(state)) {
      last_.status = status;
      last_.message = std::string("the ") + which + " state is outside the state space's bounds";
      OMPL_ERROR("%s: %s", getName().c_str(), last_.message.c_str());
      return omplStatus(status);
    }
  const cspace::Query query{toConfiguration(pdef_->getStartState(0), context_->space),
                            toConfiguration(goal->getState(), context_->space), {}};
  // OMPL's condition caches its answer in a plain bool; our planners poll from OpenMP threads.
  std::mutex ptc_mutex;
  const planners::Termination stop = planners::Termination::when([&ptc, &ptc_mutex] {
    const std::lock_guard<std::mutex> lock(ptc_mutex);
    return ptc();
  });
  const std::uint64_t seed =
      seed_ ? (*seed_)++
            : (static_cast<std::uint64_t>(rng_.uniformInt(0, std::numeric_limits<int>::max())) << 31) ^
                  static_cast<std::uint64_t>(rng_.uniformInt(0, std::numeric_limits<int>::max()));
  try {
    planners::PlanResult build;
    if (!planner_->built()) build = planner_->build(seed, stop);
    if (planner_->built()) {
      last_ = planner_->query(query, seed, stop);
      planners::addBuild(build, last_);
    } else {
      last_ = build;
    }
  } catch (const std::exception& e) {  // misuse or a segment the validator refuses (std::length_error)
    last_ = {};
    last_.status = PlanStatus::kInvalidInput;
    last_.message = e.what();
  }
  const bool approximate = last_.status == PlanStatus::kLocalMinimum;
  if (!last_.solved() && !(approximate && last_.path.size() >= 2)) {
    OMPL_INFORM("%s: %s: %s", getName().c_str(), planners::planStatusName(last_.status), last_.message.c_str());
    return approximate ? ob::PlannerStatus(ob::PlannerStatus::ABORT) : omplStatus(last_.status);  // no path to give
  }
  auto path = std::make_shared<og::PathGeometric>(si_);
  ob::State* state = si_->allocState();
  for (const Eigen::VectorXd& q : last_.path) {
    toState(q, context_->space.metricScale(), state);
    path->append(state);
  }
  si_->freeState(state);
  const double difference = approximate ? context_->space.distance(last_.path.back(), query.goal) : 0.0;
  pdef_->addSolutionPath(path, approximate, difference, getName());
  return omplStatus(last_.status);
}

void SvmOmplPlannerBase::getPlannerData(ob::PlannerData& data) const {
  ob::Planner::getPlannerData(data);
  if (!context_) return;
  const Eigen::VectorXd& scale = context_->space.metricScale();
  std::vector<ob::State*> states;
  auto vertex = [&](const Eigen::VectorXd& q) {
    states.push_back(si_->allocState());
    toState(q, scale, states.back());
    return ob::PlannerDataVertex(states.back());
  };
  // A configuration's vertex, so that the last path runs through the roadmap's own vertices.
  std::map<std::vector<double>, unsigned int> vertex_at;
  auto vertexOf = [&](const Eigen::VectorXd& q) {
    auto [it, fresh] = vertex_at.try_emplace(std::vector<double>(q.data(), q.data() + q.size()), 0u);
    if (fresh) it->second = data.addVertex(vertex(q));
    return it->second;
  };
  if (const planners::Roadmap* roadmap = planner_ ? planner_->view().roadmap : nullptr) {
    std::vector<unsigned int> index(roadmap->numNodes());
    for (int i = 0; i < roadmap->numNodes(); ++i) index[i] = vertexOf(roadmap->node(i));
    // Lazy edges no query has checked yet are candidates, not roadmap edges. Both ways, as OMPL's PRM
    // gives its undirected roadmap.
    for (int i = 0; i < roadmap->numNodes(); ++i)
      for (const planners::Edge& e : roadmap->neighbours(i))
        if (e.checked) data.addEdge(index[i], index[e.to], ob::PlannerDataEdge(), ob::Cost(e.cost));
  }
  // The path solve() gave OMPL (exact, or a local minimum's approximate one), its ends marked start
  // and goal as OMPL's own planners mark theirs.
  const bool given = last_.solved() || last_.status == planners::PlanStatus::kLocalMinimum;
  if (given && last_.path.size() >= 2) {
    for (size_t i = 1; i < last_.path.size(); ++i)
      if (const unsigned int a = vertexOf(last_.path[i - 1]), b = vertexOf(last_.path[i]); a != b)
        data.addEdge(a, b, ob::PlannerDataEdge(),
                     ob::Cost(context_->space.distance(last_.path[i - 1], last_.path[i])));
    data.markStartState(data.getVertex(vertexOf(last_.path.front())).getState());
    data.markGoalState(data.getVertex(vertexOf(last_.path.back())).getState());
  }
  data.decoupleFromPlanner();  // the data owns copies of the states; ours go
  for (ob::State* s : states) si_->freeState(s);
}

ob::PlannerPtr makeSvmOmplPlanner(const std::string& name, const ob::SpaceInformationPtr& si,
                                  cspace::ParameterSet params) {
  if (name == "svmp") return std::make_shared<SvmpOmplPlanner>(si, std::move(params));
  if (name == "prm") return std::make_shared<PrmOmplPlanner>(si, std::move(params));
  if (name == "local") return std::make_shared<LocalOmplPlanner>(si, std::move(params));
  if (name == "svpp") return std::make_shared<SvppOmplPlanner>(si, std::move(params));
  return nullptr;
}

}  // namespace svmp::ompl_planners
