#include "robots/robot.hpp"

#include <algorithm>
#include <sstream>
#include <stdexcept>

namespace svmp::robots {

Robot::Robot(std::string name, Eigen::VectorXd lower, Eigen::VectorXd upper, int workspace_dim)
    : name_(std::move(name)), lower_(std::move(lower)), upper_(std::move(upper)),
      workspace_dim_(workspace_dim) {
  if (lower_.size() != upper_.size() || lower_.size() == 0)
    throw std::invalid_argument(name_ + ": joint limits must be non-empty and of equal size");
  for (int i = 0; i < lower_.size(); ++i) {
    if (!std::isfinite(lower_[i]) || !std::isfinite(upper_[i]) || !(lower_[i] < upper_[i])) {
      std::ostringstream err;
      err << name_ << ": joint " << i + 1 << " limits must be finite with lower < upper, got ["
          << lower_[i] << ", " << upper_[i] << "]";
      throw std::invalid_argument(err.str());
    }
  }
}

bool Robot::withinLimits(const Eigen::Ref<const Eigen::VectorXd>& q) const {
  return ((q - lower_).array() >= 0).all() && ((upper_ - q).array() >= 0).all();
}

std::string Robot::linkLabel(int link) { return link == kBase ? "base" : std::to_string(link); }

std::vector<std::pair<int, int>> Robot::nonAdjacentLinkPairs() const {
  std::vector<int> solid;
  for (int i = 0; i < numLinks(); ++i)
    if (!link_shapes_[i].empty()) solid.push_back(i);
  std::vector<std::pair<int, int>> pairs;
  if (!base_shapes_.empty())
    for (int link : solid) pairs.emplace_back(kBase, link);
  for (size_t a = 0; a < solid.size(); ++a)
    for (size_t b = a + 2; b < solid.size(); ++b) pairs.emplace_back(solid[a], solid[b]);
  return pairs;
}

double Robot::displacementBound(const Eigen::Ref<const Eigen::VectorXd>& a,
                                const Eigen::Ref<const Eigen::VectorXd>& b) const {
  if (joint_reach_.size() != dof()) throw std::logic_error(name_ + ": no displacement bound set");
  return joint_reach_.dot((b - a).cwiseAbs());
}

void Robot::linkDisplacementBounds(const Eigen::Ref<const Eigen::VectorXd>& a,
                                   const Eigen::Ref<const Eigen::VectorXd>& b, Eigen::VectorXd& bounds) const {
  if (link_reach_.rows() == 0) {
    bounds.setConstant(numLinks(), displacementBound(a, b));
    return;
  }
  bounds.noalias() = link_reach_ * (b - a).cwiseAbs();
}

void Robot::setChainReach(const std::vector<double>& origin_offset) {
  const int n = numLinks();
  if (static_cast<int>(origin_offset.size()) != n || n != dof())
    throw std::logic_error(name_ + ": one origin offset per link and joint");
  std::vector<double> link_reach(n, 0.0);
  for (int k = 0; k < n; ++k)
    for (const Shape& s : link_shapes_[k]) link_reach[k] = std::max(link_reach[k], s.reach());
  link_reach_.setZero(n, n);
  for (int j = 0; j < n; ++j) {
    double along = 0;
    for (int k = j; k < n; ++k) {
      if (k > j) along += origin_offset[k];
      link_reach_(k, j) = along + link_reach[k];
    }
  }
  joint_reach_ = link_reach_.colwise().maxCoeff().transpose();
}

bool Robot::mayReach(const Eigen::AlignedBox3d& box) const {
  if (joint_reach_.size() != dof()) return true;
  Poses poses;
  linkPoses(lower_, poses);
  return box.exteriorDistance(poses[0].translation()) <= joint_reach_[0];
}

std::optional<Eigen::VectorXd> Robot::configurationAt(const Eigen::Vector3d&) const { return std::nullopt; }

double Robot::stepDisplacement(const Eigen::VectorXd& scale, double length) const {
  if (joint_reach_.size() != dof()) throw std::logic_error(name_ + ": no displacement bound set");
  return length * joint_reach_.cwiseQuotient(scale).norm();
}

void Robot::checkConfiguration(const Eigen::Ref<const Eigen::VectorXd>& q, const char* where) const {
  if (q.size() != dof()) {
    std::ostringstream err;
    err << where << ": configuration has " << q.size() << " values, robot " << name_ << " has dof "
        << dof();
    throw std::invalid_argument(err.str());
  }
  if (!q.allFinite()) {
    std::ostringstream err;
    err << where << ": configuration [" << q.transpose() << "] is not finite";
    throw std::invalid_argument(err.str());
  }
}

}  // namespace svmp::robots
