#include "cspace/scenario/scenario.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>

#include "robots/dh_arm.hpp"
#include "robots/planar_arm.hpp"
#include "robots/point_robot.hpp"

namespace svmp::cspace {
namespace {

constexpr double kPi = std::numbers::pi;

// A plain number, or a multiple of pi for angles: "pi", "-pi/2", "0.5pi", "2pi/3". False when the text
// is anything else (trailing characters included).
bool parseNumber(const std::string& s, double& v) {
  if (s.empty()) return false;
  const char* begin = s.c_str();
  char* end = nullptr;
  v = std::strtod(begin, &end);
  if (*end == '\0') return end != begin;
  double coefficient = v;
  std::string rest(end);
  if (end == begin) {  // no number before "pi", at most a sign
    const bool sign = s[0] == '-' || s[0] == '+';
    coefficient = s[0] == '-' ? -1 : 1;
    rest = s.substr(sign ? 1 : 0);
  }
  if (rest.compare(0, 2, "pi") != 0) return false;
  v = coefficient * kPi;
  rest = rest.substr(2);
  if (rest.empty()) return true;
  if (rest[0] != '/') return false;
  const char* denominator = rest.c_str() + 1;
  const double d = std::strtod(denominator, &end);
  if (end == denominator || *end != '\0') return false;
  v /= d;
  return true;
}

// Reads typed values from YAML nodes, naming "file: field 'path'" in every error.
class Reader {
 public:
  explicit Reader(std::string source) : source_(std::move(source)) {}

  [[noreturn]] void fail(const std::string& field, const std::string& what) const {
    throw ScenarioError(source_ + ": field '" + field + "': " + what);
  }
  static std::string text(const YAML::Node& n) {
    if (!n.IsDefined() || n.IsNull()) return "(missing)";
    if (n.IsScalar()) return "'" + n.Scalar() + "'";
    YAML::Emitter e;
    e << YAML::Flow << n;
    return e.c_str();
  }
  // field is the child's ("robot.type"); a parent that is not a mapping is reported under its own name.
  YAML::Node require(const YAML::Node& parent, const std::string& key, const std::string& field) const {
    requireMap(parent, parentField(field, key));
    YAML::Node n = parent[key];
    if (!n.IsDefined() || n.IsNull()) fail(field, "is required");
    return n;
  }
  double number(const YAML::Node& n, const std::string& field) const {
    if (!n.IsScalar()) fail(field, "expected a number, got " + text(n));
    double v = 0;
    if (!parseNumber(n.Scalar(), v)) fail(field, "expected a number, got " + text(n));
    if (!std::isfinite(v)) fail(field, "expected a finite number, got " + text(n));
    return v;
  }
  double positive(const YAML::Node& n, const std::string& field) const {
    const double v = number(n, field);
    if (!(v > 0)) fail(field, "must be positive, got " + text(n));
    return v;
  }
  Eigen::VectorXd vector(const YAML::Node& n, const std::string& field, int size = -1) const {
    if (!n.IsSequence()) fail(field, "expected a list of numbers, got " + text(n));
    if (size >= 0 && static_cast<int>(n.size()) != size)
      fail(field, "expected " + std::to_string(size) + " numbers, got " + std::to_string(n.size()) +
                      ": " + text(n));
    Eigen::VectorXd v(n.size());
    for (size_t i = 0; i < n.size(); ++i) v[i] = number(n[i], field + "[" + std::to_string(i) + "]");
    return v;
  }
  // yaml-cpp throws its own exception when a scalar or list is indexed by key: test first.
  void requireMap(const YAML::Node& n, const std::string& field) const {
    if (!n.IsMap()) fail(field, "expected a mapping {key: value}, got " + text(n));
  }
  static std::string parentField(const std::string& field, const std::string& key) {
    const std::string suffix = "." + key;
    if (field.size() > suffix.size() && field.compare(field.size() - suffix.size(), suffix.size(), suffix) == 0)
      return field.substr(0, field.size() - suffix.size());
    return field;
  }
  bool boolean(const YAML::Node& n, const std::string& field) const {
    if (n.IsScalar() && (n.Scalar() == "true" || n.Scalar() == "false")) return n.Scalar() == "true";
    fail(field, "expected true or false, got " + text(n));
  }
  std::string string(const YAML::Node& n, const std::string& field) const {
    if (!n.IsScalar()) fail(field, "expected text, got " + text(n));
    return n.Scalar();
  }
  const std::string& source() const { return source_; }

 private:
  std::string source_;
};

Eigen::Isometry3d readPose(const Reader& r, const YAML::Node& n, const std::string& field) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  r.requireMap(n, field);
  if (n["position"]) {
    Eigen::VectorXd p = r.vector(n["position"], field + ".position");
    if (p.size() != 2 && p.size() != 3) r.fail(field + ".position", "expected 2 or 3 numbers, got " + Reader::text(n["position"]));
    pose.translation().head(p.size()) = p;
  }
  if (n["rpy"]) {
    const Eigen::VectorXd rpy = r.vector(n["rpy"], field + ".rpy", 3);
    pose.linear() = (Eigen::AngleAxisd(rpy[2], Eigen::Vector3d::UnitZ()) *
                     Eigen::AngleAxisd(rpy[1], Eigen::Vector3d::UnitY()) *
                     Eigen::AngleAxisd(rpy[0], Eigen::Vector3d::UnitX()))
                        .toRotationMatrix();
  }
  return pose;
}

robots::Shape readShape(const Reader& r, const YAML::Node& n, const std::string& field) {
  const std::string kind = r.string(r.require(n, "shape", field + ".shape"), field + ".shape");
  robots::Shape s;
  if (kind == "box") {
    s = robots::Shape::box(r.vector(r.require(n, "size", field + ".size"), field + ".size", 3));
    for (int i = 0; i < 3; ++i)
      if (!(s.dims[i] > 0)) r.fail(field + ".size", "sides must be positive, got " + Reader::text(n["size"]));
  } else if (kind == "sphere") {
    s = robots::Shape::sphere(r.positive(r.require(n, "radius", field + ".radius"), field + ".radius"));
  } else if (kind == "cylinder" || kind == "capsule") {
    const double radius = r.positive(r.require(n, "radius", field + ".radius"), field + ".radius");
    const double length = r.positive(r.require(n, "length", field + ".length"), field + ".length");
    s = kind == "cylinder" ? robots::Shape::cylinder(radius, length) : robots::Shape::capsule(radius, length);
  } else {
    r.fail(field + ".shape", "expected box, sphere, cylinder or capsule, got '" + kind + "'");
  }
  s.pose = readPose(r, n, field);
  return s;
}

void readLimits(const Reader& r, const YAML::Node& n, const std::string& field, Eigen::VectorXd& lower,
                Eigen::VectorXd& upper, int dof) {
  lower = r.vector(r.require(n, "lower", field + ".lower"), field + ".lower", dof);
  upper = r.vector(r.require(n, "upper", field + ".upper"), field + ".upper", dof);
  for (int i = 0; i < dof; ++i)
    if (!(lower[i] < upper[i]))
      r.fail(field, "joint " + std::to_string(i + 1) + " needs lower < upper, got [" +
                        std::to_string(lower[i]) + ", " + std::to_string(upper[i]) + "]");
}

std::shared_ptr<const robots::Robot> readRobot(const Reader& r, const YAML::Node& n) {
  const std::string type = r.string(r.require(n, "type", "robot.type"), "robot.type");
  if (type == "point") {
    const YAML::Node b = r.require(n, "bounds", "robot.bounds");
    const Eigen::VectorXd lower = r.vector(r.require(b, "lower", "robot.bounds.lower"), "robot.bounds.lower");
    if (lower.size() != 2 && lower.size() != 3)
      r.fail("robot.bounds.lower", "a point robot has 2 or 3 dimensions, got " + Reader::text(b["lower"]));
    Eigen::VectorXd lo, hi;
    readLimits(r, b, "robot.bounds", lo, hi, static_cast<int>(lower.size()));
    const double radius = n["radius"] ? r.positive(n["radius"], "robot.radius") : 1e-6;
    return std::make_shared<robots::PointRobot>(lo, hi, radius);
  }
  if (type == "planar_arm") {
    const Eigen::VectorXd lengths = r.vector(r.require(n, "lengths", "robot.lengths"), "robot.lengths");
    const int dof = static_cast<int>(lengths.size());
    if (dof == 0) r.fail("robot.lengths", "needs at least one link");
    for (int i = 0; i < dof; ++i)
      if (!(lengths[i] > 0)) r.fail("robot.lengths[" + std::to_string(i) + "]", "must be positive, got " + std::to_string(lengths[i]));
    Eigen::VectorXd widths;
    const YAML::Node w = r.require(n, "widths", "robot.widths");
    widths = w.IsScalar() ? Eigen::VectorXd::Constant(dof, r.positive(w, "robot.widths"))
                          : r.vector(w, "robot.widths", dof);
    for (int i = 0; i < dof; ++i)
      if (!(widths[i] > 0)) r.fail("robot.widths[" + std::to_string(i) + "]", "must be positive, got " + std::to_string(widths[i]));
    Eigen::VectorXd lo = Eigen::VectorXd::Constant(dof, -kPi), hi = Eigen::VectorXd::Constant(dof, kPi);
    if (n["limits"]) readLimits(r, n["limits"], "robot.limits", lo, hi, dof);
    Eigen::Vector2d base = Eigen::Vector2d::Zero();
    if (n["base"]) base = r.vector(n["base"], "robot.base", 2);
    return std::make_shared<robots::PlanarArm>(
        std::vector<double>(lengths.data(), lengths.data() + dof),
        std::vector<double>(widths.data(), widths.data() + dof), lo, hi, base);
  }
  if (type == "dh_arm") {
    robots::DhArmSpec spec;
    if (n["preset"]) {
      const std::string preset = r.string(n["preset"], "robot.preset");
      if (preset == "crs_f3") {
        const int joints = n["joints"] ? static_cast<int>(r.number(n["joints"], "robot.joints")) : 6;
        if (joints != 3 && joints != 6) r.fail("robot.joints", "crs_f3 has 3 (simplified) or 6 joints, got " + Reader::text(n["joints"]));
        spec = robots::crsF3Spec(joints);
      } else if (preset == "panda") {
        spec = robots::pandaSpec();
      } else {
        r.fail("robot.preset", "expected crs_f3 or panda, got '" + preset + "'");
      }
    } else {
      const YAML::Node dh = r.require(n, "dh", "robot.dh");
      if (!dh.IsSequence() || dh.size() == 0) r.fail("robot.dh", "expected a list of rows {a, alpha, d, offset}");
      for (size_t i = 0; i < dh.size(); ++i) {
        const std::string f = "robot.dh[" + std::to_string(i) + "]";
        r.requireMap(dh[i], f);
        robots::DhRow row;
        row.a = dh[i]["a"] ? r.number(dh[i]["a"], f + ".a") : 0;
        row.alpha = dh[i]["alpha"] ? r.number(dh[i]["alpha"], f + ".alpha") : 0;
        row.d = dh[i]["d"] ? r.number(dh[i]["d"], f + ".d") : 0;
        row.offset = dh[i]["offset"] ? r.number(dh[i]["offset"], f + ".offset") : 0;
        spec.rows.push_back(row);
      }
      spec.name = n["name"] ? r.string(n["name"], "robot.name") : "dh_arm";
      spec.link_radius.assign(spec.rows.size(), 0.05);
      readLimits(r, r.require(n, "limits", "robot.limits"), "robot.limits", spec.lower, spec.upper,
                 static_cast<int>(spec.rows.size()));
    }
    const int dof = static_cast<int>(spec.rows.size());
    if (n["limits"] && n["preset"]) readLimits(r, n["limits"], "robot.limits", spec.lower, spec.upper, dof);
    if (n["link_radius"]) {
      const Eigen::VectorXd radius = r.vector(n["link_radius"], "robot.link_radius", dof);
      for (int i = 0; i < dof; ++i)
        if (!(radius[i] > 0)) r.fail("robot.link_radius[" + std::to_string(i) + "]", "must be positive, got " + std::to_string(radius[i]));
      spec.link_radius.assign(radius.data(), radius.data() + dof);
    }
    if (n["flange"]) {
      const YAML::Node f = n["flange"];
      r.requireMap(f, "robot.flange");
      spec.flange.a = f["a"] ? r.number(f["a"], "robot.flange.a") : 0;
      spec.flange.alpha = f["alpha"] ? r.number(f["alpha"], "robot.flange.alpha") : 0;
      spec.flange.d = f["d"] ? r.number(f["d"], "robot.flange.d") : 0;
    }
    if (n["base"]) spec.base = readPose(r, n["base"], "robot.base");
    if (n["tool"]) {
      if (!n["tool"].IsSequence()) r.fail("robot.tool", "expected a list of shapes");
      for (size_t i = 0; i < n["tool"].size(); ++i)
        spec.tool.push_back(readShape(r, n["tool"][i], "robot.tool[" + std::to_string(i) + "]"));
    }
    if (n["tool_tip"]) spec.tool_tip = r.vector(n["tool_tip"], "robot.tool_tip", 3);
    return std::make_shared<robots::DhArm>(spec);
  }
  r.fail("robot.type", "expected point, planar_arm or dh_arm, got '" + type + "'");
}

Eigen::VectorXd readConfiguration(const Reader& r, const YAML::Node& n, const std::string& field,
                                  const robots::Robot& robot) {
  const Eigen::VectorXd q = r.vector(n, field, robot.dof());
  if (!robot.withinLimits(q)) {
    std::ostringstream v;
    v << "[" << q.transpose() << "]";
    r.fail(field, "configuration " + v.str() + " lies outside the joint limits");
  }
  return q;
}

std::string scalarText(const YAML::Node& n) {
  return n.IsScalar() ? n.Scalar() : Reader::text(n);
}

}  // namespace

ConfigurationSpace Scenario::makeSpace() const {
  return ConfigurationSpace(robot->lowerLimits(), robot->upperLimits(), metric_weights);
}

ParameterSet Scenario::paramsFor(const std::string& planner) const {
  auto it = planner_params.find(planner);
  if (it != planner_params.end()) return it->second;
  return ParameterSet(path, "planners." + planner + ".", {});
}

namespace {

Scenario parseScenarioUnguarded(const std::string& yaml_text, const std::string& source) {
  Reader r(source);
  YAML::Node root;
  try {
    root = YAML::Load(yaml_text);
  } catch (const YAML::Exception& e) {
    throw ScenarioError(source + ": YAML syntax error at line " + std::to_string(e.mark.line + 1) +
                        ": " + e.msg);
  }
  if (!root.IsMap()) throw ScenarioError(source + ": expected a YAML mapping at the top level");
  static const std::set<std::string> known = {"name", "description", "robot", "obstacles", "start", "goal",
                                              "queries", "witness", "resolution", "metric_weights",
                                              "self_collision", "planners"};
  for (const auto& kv : root)
    if (!known.count(kv.first.Scalar())) r.fail(kv.first.Scalar(), "unknown field");

  Scenario s;
  s.path = source;
  s.name = root["name"] ? r.string(root["name"], "name") : source;
  s.description = root["description"] ? r.string(root["description"], "description") : "";
  try {
    s.robot = readRobot(r, r.require(root, "robot", "robot"));
  } catch (const std::invalid_argument& e) {
    throw ScenarioError(source + ": field 'robot': " + e.what());
  }
  const int dof = s.robot->dof();

  std::vector<Obstacle> obstacles;
  if (root["obstacles"]) {
    const YAML::Node list = root["obstacles"];
    if (!list.IsSequence()) r.fail("obstacles", "expected a list");
    for (size_t i = 0; i < list.size(); ++i) {
      const std::string f = "obstacles[" + std::to_string(i) + "]";
      r.requireMap(list[i], f);
      Obstacle o;
      o.name = list[i]["name"] ? r.string(list[i]["name"], f + ".name") : "";
      o.shape = readShape(r, list[i], f);
      if (s.robot->workspaceDim() == 2 && std::abs(o.shape.pose.translation().z()) > 0 &&
          o.shape.kind == robots::ShapeKind::kBox && 0.5 * o.shape.dims.z() < std::abs(o.shape.pose.translation().z()))
        r.fail(f + ".position", "a planar robot moves in z = 0; this obstacle does not reach it");
      o.is_virtual = list[i]["virtual"] ? r.boolean(list[i]["virtual"], f + ".virtual") : false;
      o.weight = list[i]["weight"] ? r.positive(list[i]["weight"], f + ".weight") : 1.0;
      if (list[i]["sample"]) o.root_sample = readConfiguration(r, list[i]["sample"], f + ".sample", *s.robot);
      obstacles.push_back(std::move(o));
    }
  }
  s.environment = std::make_shared<Environment>(std::move(obstacles));

  if (root["queries"]) {
    const YAML::Node list = root["queries"];
    if (!list.IsSequence() || list.size() == 0) r.fail("queries", "expected a non-empty list of {start, goal}");
    for (size_t i = 0; i < list.size(); ++i) {
      const std::string f = "queries[" + std::to_string(i) + "]";
      s.queries.push_back({readConfiguration(r, r.require(list[i], "start", f + ".start"), f + ".start", *s.robot),
                           readConfiguration(r, r.require(list[i], "goal", f + ".goal"), f + ".goal", *s.robot), {}});
    }
  } else {
    s.queries.push_back({readConfiguration(r, r.require(root, "start", "start"), "start", *s.robot),
                         readConfiguration(r, r.require(root, "goal", "goal"), "goal", *s.robot), {}});
  }
  auto readWitness = [&](const YAML::Node& n, const std::string& f, Query& q) {
    if (!n) return;
    if (!n.IsSequence()) r.fail(f, "expected a list of configurations");
    for (size_t i = 0; i < n.size(); ++i)
      q.witness.push_back(readConfiguration(r, n[i], f + "[" + std::to_string(i) + "]", *s.robot));
  };
  if (root["queries"]) {
    for (size_t i = 0; i < s.queries.size(); ++i)
      readWitness(root["queries"][i]["witness"], "queries[" + std::to_string(i) + "].witness", s.queries[i]);
  } else {
    readWitness(root["witness"], "witness", s.queries[0]);
  }

  s.resolution = r.positive(r.require(root, "resolution", "resolution"), "resolution");
  s.metric_weights = root["metric_weights"] ? r.vector(root["metric_weights"], "metric_weights", dof)
                                            : Eigen::VectorXd::Ones(dof);
  for (int i = 0; i < dof; ++i)
    if (!(s.metric_weights[i] > 0))
      r.fail("metric_weights[" + std::to_string(i) + "]", "must be positive, got " + std::to_string(s.metric_weights[i]));
  s.self_collision = root["self_collision"] ? r.boolean(root["self_collision"], "self_collision") : true;

  if (root["planners"]) {
    if (!root["planners"].IsMap()) r.fail("planners", "expected a mapping planner -> {key: value}");
    for (const auto& planner : root["planners"]) {
      const std::string name = planner.first.Scalar();
      if (!planner.second.IsMap()) r.fail("planners." + name, "expected a mapping key -> value");
      std::map<std::string, std::string> values;
      for (const auto& kv : planner.second) {
        if (!kv.second.IsScalar())
          r.fail("planners." + name + "." + kv.first.Scalar(), "expected a single value, got " + scalarText(kv.second));
        values[kv.first.Scalar()] = kv.second.Scalar();
      }
      s.planner_params.emplace(name, ParameterSet(source, "planners." + name + ".", values));
    }
  }
  return s;
}

}  // namespace

Scenario parseScenario(const std::string& yaml_text, const std::string& source) {
  try {
    return parseScenarioUnguarded(yaml_text, source);
  } catch (const YAML::Exception& e) {
    // Last line of defence for a node kind the reader did not test first: still name the file and line.
    throw ScenarioError(source + ": line " + std::to_string(e.mark.line + 1) + ": " + e.msg);
  }
}

Scenario loadScenario(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw ScenarioError(path + ": cannot open the file");
  std::stringstream text;
  text << in.rdbuf();
  return parseScenario(text.str(), path);
}

}  // namespace svmp::cspace
