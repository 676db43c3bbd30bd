#include "cspace/scenario/scenario.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>
#include <sstream>

#include "cspace/scenario/yaml_reader.hpp"
#include "robots/dh_arm.hpp"
#include "robots/planar_arm.hpp"
#include "robots/point_robot.hpp"

namespace svmp::cspace {
namespace {

using scenario_yaml::KeyList;
using scenario_yaml::num;
using scenario_yaml::Reader;
using L = ScenarioLimits;

constexpr double kPi = std::numbers::pi;

std::string idx(const std::string& field, size_t i) { return field + "[" + std::to_string(i) + "]"; }

// Lengths, widths, radii, box sides.
double length(const Reader& r, const YAML::Node& n, const std::string& field) {
  return r.inRange(n, field, L::kMinLength, L::kMaxLength, "m");
}
Eigen::VectorXd lengths(const Reader& r, const YAML::Node& n, const std::string& field, int size,
                        size_t max_size = 3) {
  return r.vector(n, field, size, L::kMinLength, L::kMaxLength, "m", max_size);
}
double angle(const Reader& r, const YAML::Node& n, const std::string& field) {
  return r.inRange(n, field, -L::kMaxAngle, L::kMaxAngle, "rad");
}
double dhLength(const Reader& r, const YAML::Node& n, const std::string& field) {
  return r.inRange(n, field, -L::kMaxDhLength, L::kMaxDhLength, "m");
}
Eigen::VectorXd position(const Reader& r, const YAML::Node& n, const std::string& field, int size) {
  return r.vector(n, field, size, -L::kMaxCoordinate, L::kMaxCoordinate, "m", 3);
}

const KeyList kPoseKeys = {"position", "rpy"};
const KeyList kShapeKeys = {"shape", "size", "radius", "length", "position", "rpy"};
const KeyList kObstacleKeys = {"name", "shape", "size", "radius", "length", "position", "rpy", "virtual", "weight", "sample"};

Eigen::Isometry3d readPose(const Reader& r, const YAML::Node& n, const std::string& field) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  r.requireMap(n, field);
  if (n["position"]) {
    const YAML::Node p = n["position"];
    if (!p.IsSequence() || (p.size() != 2 && p.size() != 3))
      r.fail(field + ".position", "expected 2 or 3 numbers, got " + Reader::text(p));
    pose.translation().head(p.size()) = position(r, p, field + ".position", static_cast<int>(p.size()));
  }
  if (n["rpy"]) {
    const Eigen::VectorXd rpy = r.vector(n["rpy"], field + ".rpy", 3, -L::kMaxAngle, L::kMaxAngle, "rad");
    pose.linear() = (Eigen::AngleAxisd(rpy[2], Eigen::Vector3d::UnitZ()) *
                     Eigen::AngleAxisd(rpy[1], Eigen::Vector3d::UnitY()) *
                     Eigen::AngleAxisd(rpy[0], Eigen::Vector3d::UnitX()))
                        .toRotationMatrix();
  }
  return pose;
}

// An obstacle or tool shape; its keys were checked against kShapeKeys (+ the obstacle's own) already.
robots::Shape readShape(const Reader& r, const YAML::Node& n, const std::string& field) {
  const std::string kind = r.string(r.require(n, "shape", field + ".shape"), field + ".shape");
  KeyList takes;
  robots::Shape s;
  if (kind == "box") {
    takes = {"size"};
    s = robots::Shape::box(lengths(r, r.require(n, "size", field + ".size"), field + ".size", 3));
  } else if (kind == "sphere") {
    takes = {"radius"};
    s = robots::Shape::sphere(length(r, r.require(n, "radius", field + ".radius"), field + ".radius"));
  } else if (kind == "cylinder" || kind == "capsule") {
    takes = {"radius", "length"};
    const double radius = length(r, r.require(n, "radius", field + ".radius"), field + ".radius");
    const double len = length(r, r.require(n, "length", field + ".length"), field + ".length");
    s = kind == "cylinder" ? robots::Shape::cylinder(radius, len) : robots::Shape::capsule(radius, len);
  } else {
    r.fail(field + ".shape", "expected box, sphere, cylinder or capsule, got " + Reader::text(n["shape"]));
  }
  for (const char* key : {"size", "radius", "length"})
    if (n[key] && std::find(takes.begin(), takes.end(), key) == takes.end())
      r.fail(field + "." + key, "a " + kind + " does not take '" + key + "' (it takes: " + Reader::join(takes) + ")");
  s.pose = readPose(r, n, field);
  return s;
}

void readLimits(const Reader& r, const YAML::Node& n, const std::string& field, Eigen::VectorXd& lower,
                Eigen::VectorXd& upper, int dof) {
  r.checkKeys(n, field, {"lower", "upper"});
  lower = r.vector(r.require(n, "lower", field + ".lower"), field + ".lower", dof, -L::kMaxCoordinate, L::kMaxCoordinate);
  upper = r.vector(r.require(n, "upper", field + ".upper"), field + ".upper", dof, -L::kMaxCoordinate, L::kMaxCoordinate);
  for (int i = 0; i < dof; ++i)
    if (!(lower[i] < upper[i]))
      r.fail(field, "joint " + std::to_string(i + 1) + " needs lower < upper, got [" + num(lower[i]) + ", " +
                        num(upper[i]) + "]");
}

const KeyList kPointKeys = {"type", "bounds", "radius"};
const KeyList kPlanarKeys = {"type", "lengths", "widths", "limits", "base"};
const KeyList kDhCommonKeys = {"type", "limits", "link_radius", "flange", "base", "tool", "tool_tip"};

KeyList plus(KeyList a, const KeyList& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

std::shared_ptr<const robots::Robot> readRobot(const Reader& r, const YAML::Node& n) {
  const KeyList all = plus(plus(plus(kPointKeys, kPlanarKeys), kDhCommonKeys), {"preset", "joints", "dh", "name"});
  KeyList unique;
  for (const auto& k : all)
    if (std::find(unique.begin(), unique.end(), k) == unique.end()) unique.push_back(k);
  r.checkKeys(n, "robot", unique);
  const std::string type = r.string(r.require(n, "type", "robot.type"), "robot.type");
  if (type == "point") {
    r.checkKeys(n, "robot", kPointKeys, "a point robot", unique);
    const YAML::Node b = r.require(n, "bounds", "robot.bounds");
    r.checkKeys(b, "robot.bounds", {"lower", "upper"});
    const YAML::Node lower = r.require(b, "lower", "robot.bounds.lower");
    if (!lower.IsSequence() || (lower.size() != 2 && lower.size() != 3))
      r.fail("robot.bounds.lower", "a point robot has 2 or 3 dimensions, got " + Reader::text(lower));
    Eigen::VectorXd lo, hi;
    readLimits(r, b, "robot.bounds", lo, hi, static_cast<int>(lower.size()));
    const double radius = n["radius"] ? length(r, n["radius"], "robot.radius") : 1e-6;
    return std::make_shared<robots::PointRobot>(lo, hi, radius);
  }
  if (type == "planar_arm") {
    r.checkKeys(n, "robot", kPlanarKeys, "a planar_arm", unique);
    const Eigen::VectorXd links = lengths(r, r.require(n, "lengths", "robot.lengths"), "robot.lengths", -1, L::kMaxJoints);
    const int dof = static_cast<int>(links.size());
    const YAML::Node w = r.require(n, "widths", "robot.widths");
    const Eigen::VectorXd widths = w.IsScalar() ? Eigen::VectorXd::Constant(dof, length(r, w, "robot.widths"))
                                                : lengths(r, w, "robot.widths", dof);
    Eigen::VectorXd lo = Eigen::VectorXd::Constant(dof, -kPi), hi = Eigen::VectorXd::Constant(dof, kPi);
    if (n["limits"]) readLimits(r, n["limits"], "robot.limits", lo, hi, dof);
    Eigen::Vector2d base = Eigen::Vector2d::Zero();
    if (n["base"]) base = position(r, n["base"], "robot.base", 2);
    return std::make_shared<robots::PlanarArm>(std::vector<double>(links.data(), links.data() + dof),
                                               std::vector<double>(widths.data(), widths.data() + dof), lo, hi, base);
  }
  if (type != "dh_arm") r.fail("robot.type", "expected point, planar_arm or dh_arm, got " + Reader::text(n["type"]));
  robots::DhArmSpec spec;
  if (n["preset"]) {
    const std::string preset = r.string(n["preset"], "robot.preset");
    if (preset == "crs_f3") {
      r.checkKeys(n, "robot", plus(kDhCommonKeys, {"preset", "joints"}), "the crs_f3 preset", unique);
      const long joints = n["joints"] ? r.integer(n["joints"], "robot.joints", 1, L::kMaxJoints) : 6;
      if (joints != 3 && joints != 6)
        r.fail("robot.joints", "crs_f3 has 3 (simplified) or 6 joints, got " + Reader::text(n["joints"]));
      spec = robots::crsF3Spec(static_cast<int>(joints));
    } else if (preset == "panda") {
      r.checkKeys(n, "robot", plus(kDhCommonKeys, {"preset"}), "the panda preset", unique);
      spec = robots::pandaSpec();
    } else {
      r.fail("robot.preset", "expected crs_f3 or panda, got " + Reader::text(n["preset"]));
    }
    if (n["limits"])
      readLimits(r, n["limits"], "robot.limits", spec.lower, spec.upper, static_cast<int>(spec.rows.size()));
  } else {
    r.checkKeys(n, "robot", plus(kDhCommonKeys, {"dh", "name"}), "a dh_arm with a dh table", unique);
    const YAML::Node dh = r.require(n, "dh", "robot.dh");
    r.requireList(dh, "robot.dh", L::kMaxJoints, "rows {a, alpha, d, offset}");
    if (dh.size() == 0) r.fail("robot.dh", "needs at least one row {a, alpha, d, offset}");
    for (size_t i = 0; i < dh.size(); ++i) {
      const std::string f = idx("robot.dh", i);
      r.checkKeys(dh[i], f, {"a", "alpha", "d", "offset"});
      robots::DhRow row;
      row.a = dh[i]["a"] ? dhLength(r, dh[i]["a"], f + ".a") : 0;
      row.alpha = dh[i]["alpha"] ? angle(r, dh[i]["alpha"], f + ".alpha") : 0;
      row.d = dh[i]["d"] ? dhLength(r, dh[i]["d"], f + ".d") : 0;
      row.offset = dh[i]["offset"] ? angle(r, dh[i]["offset"], f + ".offset") : 0;
      spec.rows.push_back(row);
    }
    spec.name = n["name"] ? r.string(n["name"], "robot.name") : "dh_arm";
    if (spec.name.empty()) r.fail("robot.name", "must not be empty");
    spec.link_radius.assign(spec.rows.size(), 0.05);
    readLimits(r, r.require(n, "limits", "robot.limits"), "robot.limits", spec.lower, spec.upper,
               static_cast<int>(spec.rows.size()));
  }
  const int dof = static_cast<int>(spec.rows.size());
  if (n["link_radius"]) {
    const Eigen::VectorXd radius = lengths(r, n["link_radius"], "robot.link_radius", dof);
    spec.link_radius.assign(radius.data(), radius.data() + dof);
  }
  if (n["flange"]) {
    const YAML::Node f = n["flange"];
    r.checkKeys(f, "robot.flange", {"a", "alpha", "d"});
    // A key not given keeps the preset's value (zero for a dh table).
    if (f["a"]) spec.flange.a = dhLength(r, f["a"], "robot.flange.a");
    if (f["alpha"]) spec.flange.alpha = angle(r, f["alpha"], "robot.flange.alpha");
    if (f["d"]) spec.flange.d = dhLength(r, f["d"], "robot.flange.d");
  }
  if (n["base"]) {
    r.checkKeys(n["base"], "robot.base", kPoseKeys);
    spec.base = readPose(r, n["base"], "robot.base");
  }
  if (n["tool"]) {
    const YAML::Node tool = n["tool"];
    r.requireList(tool, "robot.tool", L::kMaxToolShapes, "shapes");
    for (size_t i = 0; i < tool.size(); ++i) {
      r.checkKeys(tool[i], idx("robot.tool", i), kShapeKeys);
      spec.tool.push_back(readShape(r, tool[i], idx("robot.tool", i)));
    }
  }
  if (n["tool_tip"]) spec.tool_tip = position(r, n["tool_tip"], "robot.tool_tip", 3);
  return std::make_shared<robots::DhArm>(spec);
}

Eigen::VectorXd readConfiguration(const Reader& r, const YAML::Node& n, const std::string& field,
                                  const robots::Robot& robot) {
  const Eigen::VectorXd q = r.vector(n, field, robot.dof(), -L::kMaxCoordinate, L::kMaxCoordinate);
  if (!robot.withinLimits(q)) {
    // Named in the shortest form that reads back exactly: a value a rounding away from its limit must
    // not print as inside it.
    const auto exact = [](double x) {
      char buffer[32];
      return std::string(buffer, std::to_chars(buffer, buffer + sizeof buffer, x).ptr);
    };
    std::ostringstream v;
    for (int j = 0; j < q.size(); ++j)
      if (q[j] < robot.lowerLimits()[j] || q[j] > robot.upperLimits()[j])
        v << (v.tellp() > 0 ? ", " : "") << "joint " << j + 1 << " " << exact(q[j]) << " not in ["
          << exact(robot.lowerLimits()[j]) << ", " << exact(robot.upperLimits()[j]) << "]";
    std::ostringstream all;
    all << "[" << q.transpose() << "]";
    r.fail(field, "configuration " + all.str() + " lies outside the joint limits (" + v.str() + ")");
  }
  return q;
}

// Half the height a shape spans in z about its centre: exact for every kind and rotation.
double zHalfExtent(const robots::Shape& s) {
  const Eigen::Matrix3d& rotation = s.pose.linear();
  const double axis_z = std::abs(rotation(2, 2));  // world-z part of the shape's local z axis
  switch (s.kind) {
    case robots::ShapeKind::kBox:
      return 0.5 * (std::abs(rotation(2, 0)) * s.dims.x() + std::abs(rotation(2, 1)) * s.dims.y() +
                    axis_z * s.dims.z());
    case robots::ShapeKind::kSphere: return s.dims.x();
    case robots::ShapeKind::kCylinder:
      return 0.5 * axis_z * s.dims.y() + s.dims.x() * std::sqrt(std::max(0.0, 1 - axis_z * axis_z));
    case robots::ShapeKind::kCapsule: return 0.5 * axis_z * s.dims.y() + s.dims.x();
  }
  return 0;
}

// How far from z = 0 a planar robot reaches: its link frames stay in the plane, its shapes have height.
double planarHalfHeight(const robots::Robot& robot) {
  double half = 0;
  for (int k = 0; k < robot.numLinks(); ++k)
    for (const auto& shape : robot.linkShapes(k))
      half = std::max(half, std::abs(shape.pose.translation().z()) + zHalfExtent(shape));
  return half;
}

std::vector<Obstacle> readObstacles(const Reader& r, const YAML::Node& list, const robots::Robot& robot) {
  r.requireList(list, "obstacles", L::kMaxObstacles, "obstacles");
  std::vector<Obstacle> obstacles;
  std::map<std::string, size_t> names;
  for (size_t i = 0; i < list.size(); ++i) {
    const std::string f = idx("obstacles", i);
    const YAML::Node o_node = list[i];
    r.checkKeys(o_node, f, kObstacleKeys);
    Obstacle o;
    o.name = o_node["name"] ? r.string(o_node["name"], f + ".name") : "obstacle" + std::to_string(i + 1);
    if (o.name.empty()) r.fail(f + ".name", "must not be empty");
    if (const auto [it, fresh] = names.emplace(o.name, i); !fresh)
      r.fail(f + ".name", "duplicate obstacle name '" + o.name + "' (also " + idx("obstacles", it->second) + ")");
    o.shape = readShape(r, o_node, f);
    if (robot.workspaceDim() == 2) {
      const double z = o.shape.pose.translation().z(), half = zHalfExtent(o.shape), robot_half = planarHalfHeight(robot);
      if (std::abs(z) > half + robot_half)
        r.fail(f + ".position", "a planar robot moves in z = 0 (the robot spans z in [" + num(-robot_half) + ", " +
                                    num(robot_half) + "]); this obstacle spans z in [" + num(z - half) + ", " +
                                    num(z + half) + "] and does not reach it");
    }
    o.is_virtual = o_node["virtual"] ? r.boolean(o_node["virtual"], f + ".virtual") : false;
    o.weight = o_node["weight"] ? r.positiveAtMost(o_node["weight"], f + ".weight", L::kMaxWeight) : 1.0;
    if (o_node["sample"]) o.root_sample = readConfiguration(r, o_node["sample"], f + ".sample", robot);
    obstacles.push_back(std::move(o));
  }
  return obstacles;
}

void readWitness(const Reader& r, const YAML::Node& n, const std::string& f, const robots::Robot& robot, Query& q) {
  if (!n) return;
  r.requireList(n, f, L::kMaxWitnessWaypoints, "configurations (waypoints)");
  // An empty list would read as no witness, and --check would pass a straight motion it never tried.
  if (n.size() == 0) r.fail(f, "an empty list: leave the witness out, or give the waypoints between start and goal");
  q.witness.reserve(n.size());
  for (size_t i = 0; i < n.size(); ++i) q.witness.push_back(readConfiguration(r, n[i], idx(f, i), robot));
}

std::vector<Query> readQueries(const Reader& r, const YAML::Node& root, const robots::Robot& robot) {
  std::vector<Query> queries;
  if (!root["queries"]) {
    queries.push_back({readConfiguration(r, r.require(root, "start", "start"), "start", robot),
                       readConfiguration(r, r.require(root, "goal", "goal"), "goal", robot), {}});
    readWitness(r, root["witness"], "witness", robot, queries.back());
    return queries;
  }
  for (const char* key : {"start", "goal", "witness"})
    if (root[key]) r.fail(key, "give either queries or top-level start/goal/witness, not both");
  const YAML::Node list = root["queries"];
  r.requireList(list, "queries", L::kMaxQueries, "{start, goal, witness?}");
  if (list.size() == 0) r.fail("queries", "expected a non-empty list of {start, goal}");
  for (size_t i = 0; i < list.size(); ++i) {
    const std::string f = idx("queries", i);
    r.checkKeys(list[i], f, {"start", "goal", "witness"});
    queries.push_back({readConfiguration(r, r.require(list[i], "start", f + ".start"), f + ".start", robot),
                       readConfiguration(r, r.require(list[i], "goal", f + ".goal"), f + ".goal", robot), {}});
    readWitness(r, list[i]["witness"], f + ".witness", robot, queries.back());
  }
  return queries;
}

// The resolution, bounded so that a segment across the whole C-space needs at most kMaxChecksPerDiagonal checks.
double readResolution(const Reader& r, const YAML::Node& n, const robots::Robot& robot, const Eigen::VectorXd& w) {
  const double resolution = r.inRange(n, "resolution", L::kMinResolution, L::kMaxResolution);
  const Eigen::ArrayXd range = (robot.upperLimits() - robot.lowerLimits()).array();
  const double diagonal = std::sqrt((w.array() * range.square()).sum());
  if (!(diagonal / resolution <= L::kMaxChecksPerDiagonal)) {
    std::ostringstream weights;
    weights << "[" << w.transpose() << "]";
    r.fail("resolution", Reader::text(n) + " needs " + num(diagonal / resolution) +
                             " checks for a segment across the C-space diagonal (weighted length " + num(diagonal) +
                             " with metric_weights " + weights.str() + "); at most 2^30 = " +
                             num(L::kMaxChecksPerDiagonal) + " are allowed: raise resolution to at least " +
                             num(diagonal / L::kMaxChecksPerDiagonal));
  }
  return resolution;
}

Scenario parseScenarioUnguarded(const std::string& yaml_text, const std::string& source) {
  Reader r(source);
  const YAML::Node root = scenario_yaml::loadSingleDocument(yaml_text, source);
  if (!root.IsMap())
    throw ScenarioError(source + ": expected a YAML mapping at the top level, got " +
                        (root.IsNull() ? std::string("an empty document") : Reader::text(root)));
  r.checkKeys(root, "", {"name", "description", "robot", "obstacles", "start", "goal", "queries", "witness",
                         "resolution", "metric_weights", "self_collision", "planners"});

  Scenario s;
  s.path = source;
  s.name = root["name"] ? r.string(root["name"], "name") : source;  // unchanged: writers escape it
  s.description = root["description"] ? r.string(root["description"], "description") : "";
  try {
    s.robot = readRobot(r, r.require(root, "robot", "robot"));
  } catch (const std::invalid_argument& e) {
    throw ScenarioError(source + ": field 'robot': " + e.what());
  }
  const int dof = s.robot->dof();
  bool has_shape = false;
  for (int k = 0; k < s.robot->numLinks(); ++k) has_shape = has_shape || !s.robot->linkShapes(k).empty();
  if (!has_shape && !dynamic_cast<const robots::PointRobot*>(s.robot.get()))
    r.fail("robot", "has no moving collision shape (every link segment after joint 1 has zero length and "
                    "there is no tool): nothing of it could collide");
  try {
    s.environment = std::make_shared<Environment>(
        root["obstacles"] ? readObstacles(r, root["obstacles"], *s.robot) : std::vector<Obstacle>{});
  } catch (const std::invalid_argument& e) {
    throw ScenarioError(source + ": field 'obstacles': " + e.what());
  }
  s.queries = readQueries(r, root, *s.robot);
  s.queries_listed = static_cast<bool>(root["queries"]);
  s.metric_weights = Eigen::VectorXd::Ones(dof);
  if (const YAML::Node w = root["metric_weights"]) {
    if (!w.IsSequence() || w.size() != static_cast<size_t>(dof))
      r.fail("metric_weights", "expected " + std::to_string(dof) + " numbers, got " + Reader::text(w));
    for (int i = 0; i < dof; ++i) s.metric_weights[i] = r.positiveAtMost(w[i], idx("metric_weights", i), L::kMaxWeight);
  }
  s.resolution = readResolution(r, r.require(root, "resolution", "resolution"), *s.robot, s.metric_weights);
  s.self_collision = root["self_collision"] ? r.boolean(root["self_collision"], "self_collision") : true;

  if (root["planners"]) {
    const YAML::Node planners = root["planners"];
    if (!planners.IsMap()) r.fail("planners", "expected a mapping planner -> {key: value}, got " + Reader::text(planners));
    r.checkKeys(planners, "planners", {});  // planner names: duplicates; unknown ones are the planners' call
    for (const auto& planner : planners) {
      const std::string name = planner.first.Scalar();
      if (!planner.second.IsMap())
        r.fail("planners." + name, "expected a mapping key -> value, got " + Reader::text(planner.second));
      r.checkKeys(planner.second, "planners." + name, {});  // keys: ParameterSet reports unused ones
      std::map<std::string, std::string> values;
      for (const auto& kv : planner.second) {
        if (!kv.second.IsScalar())
          r.fail("planners." + name + "." + kv.first.Scalar(), "expected a single value, got " + Reader::text(kv.second));
        values[kv.first.Scalar()] = kv.second.Scalar();
      }
      s.planner_params.emplace(name, ParameterSet(source, "planners." + name + ".", values));
    }
  }
  return s;
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

static std::string contentHash(const std::string& text) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (const unsigned char c : text) h = (h ^ c) * 0x100000001b3ULL;
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h));
  return hex;
}

Scenario parseScenario(const std::string& yaml_text, const std::string& source) {
  try {
    Scenario scenario = parseScenarioUnguarded(yaml_text, source);
    scenario.content_hash = contentHash(yaml_text);
    return scenario;
  } catch (const YAML::Exception& e) {
    // Last line of defence for a node kind the reader did not test first: still name the file and line.
    throw ScenarioError(source + ": line " + std::to_string(e.mark.line + 1) + ", column " +
                        std::to_string(e.mark.column + 1) + ": " + e.msg);
  }
}

Scenario loadScenario(const std::string& path) {
  return parseScenario(scenario_yaml::readScenarioFile(path), path);
}

}  // namespace svmp::cspace
