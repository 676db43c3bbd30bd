#include "bench/experiments/scenario_check.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <optional>

#include "cspace/collision_checker.hpp"
#include "cspace/certified_motion_validator.hpp"
#include "cspace/scenario/parameters.hpp"

namespace svmp::experiments {
namespace {

// The shortest text that reads back as each coordinate (four significant digits said "[4, 3]" of a
// start 1e-6 inside a box whose face is at x = 4).
std::string format(const Eigen::VectorXd& q) {
  std::string s = "[";
  for (int i = 0; i < q.size(); ++i) s += (i ? ", " : "") + cspace::parameterText(q[i]);
  return s + "]";
}

// What q hits, naming the link pair of a self-collision.
std::string describe(const cspace::CollisionChecker& checker, int hit, const Eigen::VectorXd& q) {
  std::string what = cspace::describeHit(checker.environment(), hit);
  if (hit != cspace::kSelfCollisionHit) return what;
  if (const auto pair = checker.selfCollidingPair(q))
    what += " (links " + robots::Robot::linkLabel(pair->first) + " and " +
            robots::Robot::linkLabel(pair->second) + ")";
  return what;
}

// "" when a free configuration `clearance` from contact is far enough for a path from it to be
// proven; else why not.
std::string tooCloseToProve(const cspace::Scenario& scenario, double clearance) {
  const double tolerance = cspace::CertifiedMotionValidator::toleranceFor(scenario.resolution);
  if (clearance > tolerance) return "";
  std::ostringstream why;
  why << "free but " << clearance << " from an obstacle, within the certifier's tolerance " << tolerance
      << " (1e-6 x resolution): no motion from it can be proven collision-free";
  return why.str();
}

// The first configuration along a-b, at most `step` apart (and at most 1e6 of them), that collides,
// with what it hits.
std::optional<std::pair<Eigen::VectorXd, int>> firstHitAlong(const cspace::CollisionChecker& checker,
                                                             const cspace::ConfigurationSpace& space, double step,
                                                             const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  const double parts = std::min(1e6, std::ceil(space.distance(a, b) / step));
  Eigen::VectorXd q(a.size());
  for (double i = 1; i < parts; ++i) {
    space.interpolate(a, b, i / parts, q);
    if (const int hit = checker.check(q); hit != cspace::kFree) return std::pair{q, hit};
  }
  return std::nullopt;
}

}  // namespace

std::string droppedPairWarning(int a, int b) {
  return "links " + robots::Robot::linkLabel(a) + " and " + robots::Robot::linkLabel(b) +
         " touch in every sampled configuration and are not checked against each other";
}

bool printScenarioCheck(const cspace::Scenario& scenario, std::ostream& out) {
  const auto& robot = *scenario.robot;
  const auto& env = *scenario.environment;
  cspace::CollisionChecker checker(scenario.robot, scenario.environment, scenario.self_collision);
  const cspace::ConfigurationSpace space = scenario.makeSpace();
  out << "scenario   " << scenario.name << " (" << scenario.path << ")\n";
  if (!scenario.description.empty()) out << "           " << scenario.description << "\n";
  out << "robot      " << robot.name() << ", dof " << robot.dof() << ", " << robot.numLinks()
      << " links, " << robot.numControlPoints() << " control points, "
      << checker.selfCollisionPairs().size() << " self-collision pairs\n";
  for (const auto& [a, b] : checker.droppedSelfCollisionPairs())
    out << "warning    " << droppedPairWarning(a, b)
        << " (joined by construction, or overlapping wherever the joint limits allow)\n";
  out << "limits     lower " << format(robot.lowerLimits()) << "\n           upper "
      << format(robot.upperLimits()) << "\n";
  out << "metric     weights " << format(scenario.metric_weights) << ", resolution "
      << scenario.resolution << "\n";
  out << "obstacles  " << env.size() << " (" << env.numReal() << " real)\n";
  for (const auto& o : env.obstacles()) {
    out << "  " << std::setw(2) << o.id << " " << std::left << std::setw(16) << o.name << std::right
        << " " << robots::shapeKindName(o.shape.kind) << " dims " << format(o.shape.dims) << " at "
        << format(o.shape.pose.translation()) << (o.is_virtual ? " virtual" : "")
        << (o.weight != 1.0 ? " weight " + std::to_string(o.weight) : "") << "\n";
  }
  bool ok = true;
  for (const auto& o : env.obstacles()) {
    if (!o.root_sample) continue;
    const bool hits = checker.hits(*o.root_sample, o.id);
    ok &= hits;
    out << (hits ? "sample     " : "error      sample ") << format(*o.root_sample) << (hits ? " hits" : " does NOT hit")
        << " obstacle '" << o.name << "'" << (hits ? "" : " (planning refuses the file)") << "\n";
  }
  // A sampled motion check looks every `resolution`; between two looks the robot's points move by up
  // to `step`, so an obstacle thinner than that less the robot's own thinnest part can fall between
  // them. Certification still rejects such a path; the warning says why planners may then fail.
  const double step = robot.stepDisplacement(space.metricScale(), scenario.resolution);
  double robot_thickness = std::numeric_limits<double>::infinity();
  for (int k = 0; k < robot.numLinks(); ++k)
    for (const auto& shape : robot.linkShapes(k)) robot_thickness = std::min(robot_thickness, shape.thickness());
  for (const auto& o : env.obstacles()) {
    const double width = o.shape.thickness() + robot_thickness;
    if (o.is_virtual || !(width < step)) continue;
    out << "warning    obstacle '" << o.name << "' is " << o.shape.thickness() << " thick: one resolution step ("
        << scenario.resolution << ") moves the robot by up to " << step
        << ", so sampled motion checks may step through it (paths through it fail certification);"
        << " a resolution of at most " << scenario.resolution * width / step << " does not\n";
  }
  // The file's bound (2^30 checks across the space) keeps one motion's check finite; a run checks
  // thousands of motions, so a resolution far finer than the problem's features makes it slow (1e-9
  // in half a unit square: about 25 minutes for prm) without being wrong.
  constexpr double kManyChecksPerDiagonal = 1e6;
  if (const double diagonal = space.distance(space.lower(), space.upper());
      diagonal / scenario.resolution > kManyChecksPerDiagonal)
    out << "warning    resolution " << scenario.resolution << ": a motion across the space takes "
        << std::setprecision(3) << diagonal / scenario.resolution << std::setprecision(6)
        << " collision checks, and a run checks many motions: it may be slow\n";
  const cspace::CertifiedMotionValidator certifier(checker, space, scenario.resolution);
  for (size_t i = 0; i < scenario.queries.size(); ++i) {
    const auto& q = scenario.queries[i];
    for (const auto& [label, config] : {std::pair{"start", &q.start}, std::pair{"goal ", &q.goal}}) {
      const int hit = checker.check(*config);
      const double clearance = hit == cspace::kFree ? checker.clearance(*config) : 0;
      const std::string too_close = hit == cspace::kFree ? tooCloseToProve(scenario, clearance) : "";
      ok &= hit == cspace::kFree && too_close.empty();
      out << "query " << i << "    " << label << " " << format(*config) << "  " << describe(checker, hit, *config);
      if (hit == cspace::kFree) out << ", clearance " << std::setprecision(4) << clearance;
      if (!too_close.empty()) out << "\nerror      the " << (label[0] == 's' ? "start" : "goal") << " is " << too_close;
      out << "\n";
    }
    const std::vector<Eigen::VectorXd> path = q.witnessPath();
    if (path.empty()) continue;
    size_t failed = path.size();  // the first segment not certified
    double min_clearance = std::numeric_limits<double>::infinity();
    for (size_t k = 0; k + 1 < path.size() && failed == path.size(); ++k) {
      if (checker.isValid(path[k + 1]) && certifier.isValid(path[k], path[k + 1]))
        min_clearance = std::min(min_clearance, checker.clearance(path[k + 1]));
      else
        failed = k;
    }
    out << "query " << i << "    witness path of " << path.size() - 1 << " segments ";
    if (failed == path.size()) {
      out << "is certified collision-free, waypoint clearance >= " << min_clearance << "\n";
      continue;
    }
    ok = false;
    const int hit = checker.check(path[failed + 1]);
    out << "is NOT certified collision-free: segment " << failed << " ";
    if (hit != cspace::kFree)
      out << "ends " << describe(checker, hit, path[failed + 1]) << "\n";
    else if (const auto inside = firstHitAlong(checker, space, scenario.resolution / 4, path[failed], path[failed + 1]))
      out << "is " << describe(checker, inside->second, inside->first) << " at " << format(inside->first) << "\n";
    else
      out << "is not proven free, though no configuration along it at resolution/4 collides (it passes closer to "
             "an obstacle than the certifier can prove)\n";
  }
  return ok;
}

void requireValidConfigurations(const cspace::Scenario& scenario) {
  const cspace::CollisionChecker checker(scenario.robot, scenario.environment, scenario.self_collision);
  for (size_t i = 0; i < scenario.queries.size(); ++i) {
    const auto& q = scenario.queries[i];
    for (const auto& [key, config] : {std::pair{"start", &q.start}, std::pair{"goal", &q.goal}}) {
      const int hit = checker.check(*config);
      const std::string why = hit != cspace::kFree ? describe(checker, hit, *config)
                                                   : tooCloseToProve(scenario, checker.clearance(*config));
      if (why.empty()) continue;
      const std::string field =
          scenario.queries_listed ? "queries[" + std::to_string(i) + "]." + key : std::string(key);
      throw cspace::ScenarioError(scenario.path + ": field '" + field + "': configuration " + format(*config) +
                                  " is " + why);
    }
  }
  const auto& obstacles = scenario.environment->obstacles();
  for (size_t i = 0; i < obstacles.size(); ++i)
    if (obstacles[i].root_sample && !checker.hits(*obstacles[i].root_sample, obstacles[i].id))
      throw cspace::ScenarioError(scenario.path + ": field 'obstacles[" + std::to_string(i) + "].sample': configuration " +
                                  format(*obstacles[i].root_sample) + " does not hit obstacle '" +
                                  obstacles[i].name + "'");
}

}  // namespace svmp::experiments
