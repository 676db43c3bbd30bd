#include "robots/dh_arm.hpp"

#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>

namespace svmp::robots {
namespace {

constexpr double kPi = std::numbers::pi;

// A frame's rotation columns and origin in the world, advanced through DH rows in closed form: frame
// i's origin moves by R (a, -sin(alpha) d, cos(alpha) d) and its rotation is R RotX(alpha) RotZ(theta),
// written out column by column: composing Eigen isometries per row cost most of a collision check on
// the arms.
struct DhFrame {
  Eigen::Vector3d c0, c1, c2, p;

  explicit DhFrame(const Eigen::Isometry3d& base)
      : c0(base.linear().col(0)), c1(base.linear().col(1)), c2(base.linear().col(2)), p(base.translation()) {}

  void advance(const DhRow& row, double ca, double sa, double theta) {
    p += row.a * c0 + (ca * row.d) * c2 - (sa * row.d) * c1;
    const double ct = std::cos(theta), st = std::sin(theta);
    const Eigen::Vector3d y = ca * c1 + sa * c2;  // RotX(alpha)'s y and z columns in the world
    c2 = ca * c2 - sa * c1;
    c1 = ct * y - st * c0;
    c0 = ct * c0 + st * y;
  }

  Eigen::Isometry3d pose() const {
    Eigen::Isometry3d t;
    t.linear().col(0) = c0;
    t.linear().col(1) = c1;
    t.linear().col(2) = c2;
    t.translation() = p;
    t.makeAffine();
    return t;
  }
};

bool near(double a, double b) { return std::abs(a - b) < 1e-12; }

double wrapAngle(double a) {
  a = std::remainder(a, 2 * kPi);
  return a <= -kPi ? a + 2 * kPi : a;
}

// The segment(s) from a frame's origin to the next joint origin, in that frame: along x by a, then
// along the next frame's z by d.
void addSegmentCapsules(const DhRow& next, double radius, std::vector<Shape>& shapes) {
  const Eigen::Vector3d corner(next.a, 0, 0);
  const Eigen::Vector3d end =
      corner + next.d * Eigen::Vector3d(0, -std::sin(next.alpha), std::cos(next.alpha));
  if (next.a != 0) shapes.push_back(Shape::capsuleBetween(Eigen::Vector3d::Zero(), corner, radius));
  if (next.d != 0) shapes.push_back(Shape::capsuleBetween(corner, end, radius));
}

}  // namespace

DhArm::DhArm(DhArmSpec spec)
    : Robot(spec.name, spec.lower, spec.upper, 3), spec_(std::move(spec)) {
  const size_t n = spec_.rows.size();
  if (n != static_cast<size_t>(dof()) || spec_.link_radius.size() != n)
    throw std::invalid_argument(name_ + ": DH rows, link radii and joint limits must have equal sizes");
  for (size_t i = 0; i < n; ++i) {
    const DhRow& r = spec_.rows[i];
    if (!std::isfinite(r.a + r.alpha + r.d + r.offset))
      throw std::invalid_argument(name_ + ": DH row " + std::to_string(i + 1) + " is not finite");
    if (!(spec_.link_radius[i] > 0))
      throw std::invalid_argument(name_ + ": link " + std::to_string(i + 1) + " radius must be positive");
  }
  // Row 1 moves frame 1's origin before joint 1 turns (modified DH), so that segment is static.
  addSegmentCapsules(spec_.rows[0], spec_.link_radius[0], base_shapes_);
  for (Shape& shape : base_shapes_) shape.pose = spec_.base * shape.pose;
  link_shapes_.resize(n);
  for (size_t i = 0; i < n; ++i) {
    const DhRow& next = i + 1 < n ? spec_.rows[i + 1] : spec_.flange;
    addSegmentCapsules(next, spec_.link_radius[i], link_shapes_[i]);
  }
  for (size_t i = 0; i <= n; ++i) {
    const DhRow& row = i < n ? spec_.rows[i] : spec_.flange;
    cos_alpha_.push_back(std::cos(row.alpha));
    sin_alpha_.push_back(std::sin(row.alpha));
  }
  DhFrame flange(Eigen::Isometry3d::Identity());
  flange.advance(spec_.flange, cos_alpha_[n], sin_alpha_[n], spec_.flange.offset);
  const Eigen::Isometry3d to_flange = flange.pose();
  for (Shape shape : spec_.tool) {
    const std::string err = shape.validate();
    if (!err.empty()) throw std::invalid_argument(name_ + ": tool shape: " + err);
    if (shape.kind == ShapeKind::kBox) {
      Eigen::Index axis = 0;
      shape.dims.maxCoeff(&axis);
      const Eigen::Vector3d half = 0.5 * shape.dims[axis] * shape.pose.linear().col(axis);
      tool_points_.push_back(shape.pose.translation() + half);
      tool_points_.push_back(shape.pose.translation() - half);
    }
    shape.pose = to_flange * shape.pose;
    link_shapes_.back().push_back(shape);
  }
  // Row k moves frame k's origin from frame k - 1's by a along x and d along the rotated z, which
  // is perpendicular to x: by hypot(a, d) whatever the joint angles.
  std::vector<double> offsets(n, 0.0);
  for (size_t k = 1; k < n; ++k) offsets[k] = std::hypot(spec_.rows[k].a, spec_.rows[k].d);
  setChainReach(offsets);
  // Frame 1's origin never moves; frame k's origin is new when row k translates.
  for (size_t k = 1; k < n; ++k)
    if (spec_.rows[k].a != 0 || spec_.rows[k].d != 0) moving_origins_.push_back(static_cast<int>(k));
  const bool tip_is_last_origin =
      spec_.flange.a == 0 && spec_.flange.d == 0 && spec_.tool_tip.isZero();
  if (tip_is_last_origin && !moving_origins_.empty() && moving_origins_.back() == static_cast<int>(n) - 1)
    moving_origins_.pop_back();
}

void DhArm::linkPoses(const Eigen::Ref<const Eigen::VectorXd>& q, Poses& poses) const {
  poses.resize(spec_.rows.size());
  DhFrame frame(spec_.base);
  for (size_t i = 0; i < spec_.rows.size(); ++i) {
    frame.advance(spec_.rows[i], cos_alpha_[i], sin_alpha_[i], q[i] + spec_.rows[i].offset);
    poses[i] = frame.pose();
  }
}

Eigen::Isometry3d DhArm::flangePose(const Eigen::Ref<const Eigen::VectorXd>& q) const {
  DhFrame frame(spec_.base);
  for (size_t i = 0; i < spec_.rows.size(); ++i)
    frame.advance(spec_.rows[i], cos_alpha_[i], sin_alpha_[i], q[i] + spec_.rows[i].offset);
  const size_t n = spec_.rows.size();
  frame.advance(spec_.flange, cos_alpha_[n], sin_alpha_[n], spec_.flange.offset);
  return frame.pose();
}

// The closed-form product of the DH rows (DhFrame), as the FK kernel evaluates it at every query.
void DhArm::controlPoints(const Eigen::Ref<const Eigen::VectorXd>& q, Eigen::Matrix3Xd& points) const {
  points.resize(3, numControlPoints());
  DhFrame frame(spec_.base);
  size_t next = 0;
  for (size_t i = 0; i < spec_.rows.size(); ++i) {
    frame.advance(spec_.rows[i], cos_alpha_[i], sin_alpha_[i], q[i] + spec_.rows[i].offset);
    if (next < moving_origins_.size() && moving_origins_[next] == static_cast<int>(i)) points.col(next++) = frame.p;
  }
  const size_t n = spec_.rows.size();
  frame.advance(spec_.flange, cos_alpha_[n], sin_alpha_[n], spec_.flange.offset);
  auto inFlange = [&](const Eigen::Vector3d& v) {
    return Eigen::Vector3d(frame.p + v.x() * frame.c0 + v.y() * frame.c1 + v.z() * frame.c2);
  };
  points.col(next++) = inFlange(spec_.tool_tip);
  for (const Eigen::Vector3d& v : tool_points_) points.col(next++) = inFlange(v);
}

namespace {

// Direction of the forearm (towards the wrist centre) in frame 3.
Eigen::Vector3d forearmAxis(const DhArmSpec& s) {
  const DhRow& fourth = s.rows.size() > 3 ? s.rows[3] : s.flange;
  return Eigen::Vector3d(0, -std::sin(fourth.alpha), std::cos(fourth.alpha));
}

}  // namespace

bool DhArm::hasElbowStructure() const {
  const auto& r = spec_.rows;
  const bool ok = r.size() >= 3 && near(r[0].alpha, 0) && near(r[0].a, 0) &&
                  near(std::abs(r[1].alpha), kPi / 2) && near(r[2].alpha, 0) && near(r[1].d, 0) &&
                  near(r[2].d, 0);
  const DhRow& fourth = r.size() > 3 ? r[3] : spec_.flange;
  return ok && near(fourth.a, 0) && near(std::abs(fourth.alpha), kPi / 2);
}

Eigen::Vector3d DhArm::pointOnLinkFirstThree(const Eigen::Ref<const Eigen::VectorXd>& q, int link,
                                             double s) const {
  if (link < 1 || link > 3) throw std::invalid_argument(name_ + ": IK link must be 1, 2 or 3");
  DhFrame frame(spec_.base);
  for (int i = 0; i < link; ++i)
    frame.advance(spec_.rows[i], cos_alpha_[i], sin_alpha_[i], q[i] + spec_.rows[i].offset);
  const Eigen::Vector3d local = link == 3 ? Eigen::Vector3d(s * forearmAxis(spec_))
                                          : Eigen::Vector3d(s, 0, 0);
  return frame.pose() * local;
}

std::vector<Eigen::VectorXd> DhArm::solvePointOnLinkFirstThree(
    int link, double s, const Eigen::Vector3d& target,
    const Eigen::Ref<const Eigen::VectorXd>& seed) const {
  if (!hasElbowStructure())
    throw std::logic_error(name_ + ": closed-form IK needs the CRS-F3 elbow structure");
  checkConfiguration(seed, "DH IK seed");
  if (link < 1 || link > 3) throw std::invalid_argument(name_ + ": IK link must be 1, 2 or 3");
  const auto& r = spec_.rows;
  const Eigen::Vector3d pb = spec_.base.inverse() * target;
  std::vector<Eigen::VectorXd> candidates;
  const double base_angle = std::atan2(pb.y(), pb.x());
  for (double phi1 : {base_angle, base_angle + kPi}) {
    // Frame-1 coordinates: the arm moves in frame 1's x-z plane, so phi1 zeroes the y component.
    const Eigen::Vector3d p1 = Eigen::AngleAxisd(-phi1, Eigen::Vector3d::UnitZ()) * pb -
                               Eigen::Vector3d(0, 0, r[0].d);
    const Eigen::Vector3d w =
        Eigen::AngleAxisd(-r[1].alpha, Eigen::Vector3d::UnitX()) * p1 - Eigen::Vector3d(r[1].a, 0, 0);
    Eigen::VectorXd q = seed;
    q[0] = wrapAngle(phi1 - r[0].offset);
    if (link == 1) {
      q[0] = wrapAngle(phi1 - r[0].offset);
      candidates.push_back(q);  // exact only when the target is on the offset; verified below
      continue;
    }
    const double phi_w = std::atan2(w.y(), w.x());
    if (link == 2) {
      q[1] = wrapAngle(phi_w - r[1].offset);
      candidates.push_back(q);
      continue;
    }
    // Two-link problem in frame 2's x-y plane: upper arm a2 along x, forearm s along `axis` rotated by
    // phi3, with axis = (cos beta, sin beta).
    const Eigen::Vector3d axis = forearmAxis(spec_);
    const double beta = std::atan2(axis.y(), axis.x());
    const double l1 = r[2].a, l2 = s;
    const double c = (w.head<2>().squaredNorm() - l1 * l1 - l2 * l2) / (2 * l1 * l2);
    if (c < -1 - 1e-12 || c > 1 + 1e-12) continue;
    const double psi0 = std::acos(std::clamp(c, -1.0, 1.0));
    for (double psi : {psi0, -psi0}) {
      const double phi2 = phi_w - std::atan2(l2 * std::sin(psi), l1 + l2 * std::cos(psi));
      q[1] = wrapAngle(phi2 - r[1].offset);
      q[2] = wrapAngle(psi - beta - r[2].offset);
      candidates.push_back(q);
      if (std::abs(c) >= 1 - 1e-12) break;  // stretched or folded: both elbows coincide
    }
  }
  // Keep the exact solutions (the branch formulas above leave sign conventions to this check).
  std::vector<Eigen::VectorXd> solutions;
  const double tol = 1e-9 * std::max(1.0, target.norm());
  for (const auto& q : candidates)
    if ((pointOnLinkFirstThree(q, link, s) - target).norm() < tol) solutions.push_back(q);
  return solutions;
}

DhArmSpec crsF3Spec(int joints) {
  if (joints != 3 && joints != 6)
    throw std::invalid_argument("crs_f3: joints must be 3 (simplified model) or 6, got " +
                                std::to_string(joints));
  DhArmSpec s;
  s.name = joints == 6 ? "crs_f3" : "crs_f3_3dof";
  // Thesis Table 4.3, written as {a_{i-1}, alpha_{i-1}, d_i, theta_i offset} (DhRow's order).
  const std::vector<DhRow> table = {{0, 0, 0.35, 0},        {0.1, kPi / 2, 0, kPi / 2},
                                    {0.265, 0, 0, 0},       {0, kPi / 2, 0.27, 0},
                                    {0, -kPi / 2, 0, 0},    {0, kPi / 2, 0.075, 0}};
  // Assumed limits (deg): +-180, +-110, +-125, +-180, +-110, +-180; see docs/scenarios.md.
  const std::vector<double> limit_deg = {180, 110, 125, 180, 110, 180};
  const std::vector<double> radius = {0.06, 0.045, 0.04, 0.035, 0.035, 0.03};
  s.rows.assign(table.begin(), table.begin() + joints);
  s.lower.resize(joints);
  s.upper.resize(joints);
  for (int i = 0; i < joints; ++i) {
    s.upper[i] = limit_deg[i] * kPi / 180;
    s.lower[i] = -s.upper[i];
    s.link_radius.push_back(radius[i]);
  }
  // The simplified model ends at the wrist centre: its "flange" is joint 4's origin.
  if (joints == 3) s.flange = {0, kPi / 2, 0.27, 0};
  return s;
}

DhArmSpec pandaSpec() {
  DhArmSpec s;
  s.name = "panda";
  s.rows = {{0, 0, 0.333, 0},          {0, -kPi / 2, 0, 0},      {0, kPi / 2, 0.316, 0},
            {0.0825, kPi / 2, 0, 0},   {-0.0825, -kPi / 2, 0.384, 0},
            {0, kPi / 2, 0, 0},        {0.088, kPi / 2, 0, 0}};
  s.lower.resize(7);
  s.upper.resize(7);
  s.lower << -2.8973, -1.7628, -2.8973, -3.0718, -2.8973, -0.0175, -2.8973;
  s.upper << 2.8973, 1.7628, 2.8973, -0.0698, 2.8973, 3.7525, 2.8973;
  s.link_radius = {0.06, 0.06, 0.06, 0.055, 0.055, 0.05, 0.04};
  s.flange = {0, 0, 0.107, 0};
  return s;
}

}  // namespace svmp::robots
