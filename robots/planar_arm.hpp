#pragma once
// Planar N-link arm with revolute joints in the plane z = 0 (thesis Figs 2.6, 4.4, 4.6). Joint i is at
// the end of link i-1; angles are relative to the previous link. Each link is a box of its length and
// width (and the same thickness in z), from its joint to the next.
#include <optional>

#include "robots/robot.hpp"

namespace svmp::robots {

class PlanarArm final : public Robot {
 public:
  PlanarArm(std::vector<double> lengths, std::vector<double> widths, const Eigen::VectorXd& lower,
            const Eigen::VectorXd& upper, Eigen::Vector2d base = Eigen::Vector2d::Zero());

  const std::vector<double>& lengths() const { return lengths_; }
  const std::vector<double>& widths() const { return widths_; }
  const Eigen::Vector2d& base() const { return base_; }

  void linkPoses(const Eigen::Ref<const Eigen::VectorXd>& q, Poses& poses) const override;
  void controlPoints(const Eigen::Ref<const Eigen::VectorXd>& q, Eigen::Matrix3Xd& points) const override;
  int numControlPoints() const override { return dof(); }
  // Position of the point at distance s along link `link`'s centre line.
  Eigen::Vector2d pointOnLink(const Eigen::Ref<const Eigen::VectorXd>& q, int link, double s) const;

  // Closed-form IK (used by the local planner's obstacle sampling, thesis ch. 2.2.1): configurations
  // that put the point at distance s (0 < s <= length) along link `link` onto `target`. Joints before
  // link-1 and after `link` are copied from `seed` (the caller samples them); joints link-1 and link are
  // solved, giving both elbow solutions. For link 0 only joint 0 is solved and |target - base| must
  // equal s. Joint limits are not applied here. Angles are wrapped to (-pi, pi].
  std::vector<Eigen::VectorXd> solvePointOnLink(int link, double s, const Eigen::Vector2d& target,
                                                const Eigen::Ref<const Eigen::VectorXd>& seed) const;

 private:
  std::vector<double> lengths_, widths_;
  Eigen::Vector2d base_;
};

}  // namespace svmp::robots
