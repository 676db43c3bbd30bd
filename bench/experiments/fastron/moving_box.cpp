#include "bench/experiments/fastron/moving_box.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace svmp::experiments::fastron {

MovingBox::MovingBox(const MovingBoxOptions& options, std::mt19937_64& rng) : options_(options) {
  std::uniform_real_distribution<double> side(options.min_side, options.max_side), unit(0, 1);
  sides_ = Eigen::Vector3d(side(rng), side(rng), side(rng));
  const double r = options.ring_inner + (options.ring_outer - options.ring_inner) * unit(rng);
  const double phi = 2 * std::numbers::pi * unit(rng);
  centre_ = Eigen::Vector3d(r * std::cos(phi), r * std::sin(phi),
                            options.z_low + (options.z_high - options.z_low) * unit(rng));
}

MovingBox::MovingBox(const MovingBoxOptions& options, const Eigen::Vector3d& sides, const Eigen::Isometry3d& pose)
    : options_(options), sides_(sides), centre_(pose.translation()), rotation_(pose.linear()) {}

bool MovingBox::inRegion(const MovingBoxOptions& options, const Eigen::Vector3d& centre) {
  const double r = centre.head<2>().norm();
  return r >= options.ring_inner && r <= options.ring_outer && centre.z() >= options.z_low && centre.z() <= options.z_high;
}

void MovingBox::move(std::mt19937_64& rng) {
  std::normal_distribution<double> normal(0, 1);
  Eigen::Vector3d direction(normal(rng), normal(rng), normal(rng));
  centre_ += options_.move * direction.normalized();
  keepInside();
}

void MovingBox::keepInside() {
  const double r = centre_.head<2>().norm();
  if (r < options_.ring_inner || r > options_.ring_outer) {
    // Reflected, and clamped where one move reaches beyond the ring's width.
    const double target = std::clamp(r < options_.ring_inner ? 2 * options_.ring_inner - r : 2 * options_.ring_outer - r,
                                     options_.ring_inner, options_.ring_outer);
    const Eigen::Vector2d dir = r > 1e-12 ? Eigen::Vector2d(centre_.head<2>() / r) : Eigen::Vector2d(1, 0);
    centre_.head<2>() = target * dir;
  }
  if (centre_.z() < options_.z_low) centre_.z() = 2 * options_.z_low - centre_.z();
  if (centre_.z() > options_.z_high) centre_.z() = 2 * options_.z_high - centre_.z();
  centre_.z() = std::clamp(centre_.z(), options_.z_low, options_.z_high);
}

std::shared_ptr<const cspace::Environment> MovingBox::environment(const std::vector<cspace::Obstacle>& fixed) const {
  cspace::Obstacle box;
  box.name = "box";
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = rotation_;
  pose.translation() = centre_;
  box.shape = robots::Shape::box(sides_, pose);
  std::vector<cspace::Obstacle> obstacles = {box};
  obstacles.insert(obstacles.end(), fixed.begin(), fixed.end());
  return std::make_shared<const cspace::Environment>(obstacles);
}

std::unique_ptr<cspace::CollisionChecker> MovingBox::checker(const cspace::Scenario& scenario,
                                                             const std::vector<cspace::Obstacle>& fixed) const {
  return std::make_unique<cspace::CollisionChecker>(scenario.robot, environment(fixed), scenario.self_collision);
}

}  // namespace svmp::experiments::fastron
