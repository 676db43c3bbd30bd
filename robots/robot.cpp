#include "robots/robot.hpp"

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

std::vector<std::pair<int, int>> Robot::nonAdjacentLinkPairs() const {
  std::vector<int> solid;
  for (int i = 0; i < numLinks(); ++i)
    if (!link_shapes_[i].empty()) solid.push_back(i);
  std::vector<std::pair<int, int>> pairs;
  for (size_t a = 0; a < solid.size(); ++a)
    for (size_t b = a + 2; b < solid.size(); ++b) pairs.emplace_back(solid[a], solid[b]);
  return pairs;
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
