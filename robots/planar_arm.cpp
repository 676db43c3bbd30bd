#include "robots/planar_arm.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace svmp::robots {
namespace {

double wrapAngle(double a) {
  a = std::remainder(a, 2 * std::numbers::pi);
  return a <= -std::numbers::pi ? a + 2 * std::numbers::pi : a;
}

}  // namespace

PlanarArm::PlanarArm(std::vector<double> lengths, std::vector<double> widths,
                     const Eigen::VectorXd& lower, const Eigen::VectorXd& upper, Eigen::Vector2d base)
    : Robot("planar" + std::to_string(lengths.size()), lower, upper, 2),
      lengths_(std::move(lengths)), widths_(std::move(widths)), base_(base) {
  if (lengths_.size() != static_cast<size_t>(dof()) || widths_.size() != lengths_.size())
    throw std::invalid_argument("planar arm: lengths, widths and joint limits must have equal sizes");
  for (size_t i = 0; i < lengths_.size(); ++i) {
    if (!(lengths_[i] > 0) || !(widths_[i] > 0) || !std::isfinite(lengths_[i] + widths_[i]))
      throw std::invalid_argument("planar arm: link " + std::to_string(i + 1) +
                                  " length and width must be positive");
    Eigen::Isometry3d centre = Eigen::Isometry3d::Identity();
    centre.translation() = Eigen::Vector3d(0.5 * lengths_[i], 0, 0);
    link_shapes_.push_back(
        {Shape::box(Eigen::Vector3d(lengths_[i], widths_[i], widths_[i]), centre)});
  }
  std::vector<double> offsets(lengths_.size(), 0.0);  // joint k sits at the end of link k - 1
  for (size_t k = 1; k < lengths_.size(); ++k) offsets[k] = lengths_[k - 1];
  setChainReach(offsets);
}

void PlanarArm::linkPoses(const Eigen::Ref<const Eigen::VectorXd>& q, Poses& poses) const {
  poses.resize(lengths_.size());
  double angle = 0;
  Eigen::Vector2d joint = base_;
  for (size_t i = 0; i < lengths_.size(); ++i) {
    angle += q[i];
    const double c = std::cos(angle), s = std::sin(angle);
    Eigen::Isometry3d& pose = poses[i];
    pose.setIdentity();
    pose.linear().topLeftCorner<2, 2>() << c, -s, s, c;
    pose.translation().head<2>() = joint;
    joint += lengths_[i] * Eigen::Vector2d(c, s);
  }
}

void PlanarArm::controlPoints(const Eigen::Ref<const Eigen::VectorXd>& q,
                              Eigen::Matrix3Xd& points) const {
  // Joint 1 sits on the base and never moves: the points are joints 2..n and the tip.
  points.setZero(3, dof());
  double angle = 0;
  Eigen::Vector2d joint = base_;
  for (int i = 0; i < dof(); ++i) {
    angle += q[i];
    joint += lengths_[i] * Eigen::Vector2d(std::cos(angle), std::sin(angle));
    points.col(i).head<2>() = joint;
  }
}

Eigen::Vector2d PlanarArm::pointOnLink(const Eigen::Ref<const Eigen::VectorXd>& q, int link,
                                       double s) const {
  double angle = 0;
  Eigen::Vector2d joint = base_;
  for (int i = 0; i < link; ++i) {
    angle += q[i];
    joint += lengths_[i] * Eigen::Vector2d(std::cos(angle), std::sin(angle));
  }
  angle += q[link];
  return joint + s * Eigen::Vector2d(std::cos(angle), std::sin(angle));
}

std::vector<Eigen::VectorXd> PlanarArm::solvePointOnLink(
    int link, double s, const Eigen::Vector2d& target,
    const Eigen::Ref<const Eigen::VectorXd>& seed) const {
  if (link < 0 || link >= dof()) throw std::invalid_argument("planar IK: link index out of range");
  if (!(s > 0) || s > lengths_[link] + 1e-12)
    throw std::invalid_argument("planar IK: s must lie in (0, link length]");
  checkConfiguration(seed, "planar IK seed");
  std::vector<Eigen::VectorXd> solutions;
  if (link == 0) {
    const Eigen::Vector2d d = target - base_;
    if (std::abs(d.norm() - s) > 1e-9 * std::max(1.0, s)) return solutions;
    Eigen::VectorXd q = seed;
    q[0] = wrapAngle(std::atan2(d.y(), d.x()));
    solutions.push_back(q);
    return solutions;
  }
  // Two-link problem: joint j = link-1 at `joint`, first segment lengths_[j], second segment s.
  const int j = link - 1;
  double phi = 0;
  Eigen::Vector2d joint = base_;
  for (int i = 0; i < j; ++i) {
    phi += seed[i];
    joint += lengths_[i] * Eigen::Vector2d(std::cos(phi), std::sin(phi));
  }
  const Eigen::Vector2d d = target - joint;
  const double l1 = lengths_[j], l2 = s, r2 = d.squaredNorm();
  const double c2 = (r2 - l1 * l1 - l2 * l2) / (2 * l1 * l2);
  if (c2 < -1 - 1e-12 || c2 > 1 + 1e-12) return solutions;
  const double elbow = std::acos(std::clamp(c2, -1.0, 1.0));
  for (double q2 : {elbow, -elbow}) {
    Eigen::VectorXd q = seed;
    q[j] = wrapAngle(std::atan2(d.y(), d.x()) -
                     std::atan2(l2 * std::sin(q2), l1 + l2 * std::cos(q2)) - phi);
    q[link] = wrapAngle(q2);
    solutions.push_back(q);
    // Stretched (c2 = 1) or folded (c2 = -1, where +pi and -pi wrap to the same angle): one solution.
    if (std::abs(c2) >= 1 - 1e-12) break;
  }
  return solutions;
}

}  // namespace svmp::robots
