#include "planners/ik_obstacle_sampler.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>

#include "robots/dh_arm.hpp"
#include "robots/planar_arm.hpp"

namespace svmp::planners {
namespace {

constexpr double kPi = std::numbers::pi;

int steps(double length, double resolution) {
  return std::max(1, static_cast<int>(std::ceil(length / resolution)));
}

// Grid points on a box's six faces (box frame), spaced about `res`.
void boxSurface(const Eigen::Vector3d& sides, double res, std::vector<Eigen::Vector3d>& out) {
  const Eigen::Vector3d h = 0.5 * sides;
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    const int nu = steps(sides[u], res), nv = steps(sides[v], res);
    for (double sign : {-1.0, 1.0})
      for (int i = 0; i <= nu; ++i)
        for (int j = 0; j <= nv; ++j) {
          Eigen::Vector3d p;
          p[axis] = sign * h[axis];
          p[u] = -h[u] + sides[u] * i / nu;
          p[v] = -h[v] + sides[v] * j / nv;
          out.push_back(p);
        }
  }
}

// At least as many points as surfacePoints gives: a convex outline is no longer than the circle
// round its bounding box, and a convex surface has no more area than that box's sphere.
double surfacePointBound(const robots::Shape& shape, double res, bool planar) {
  const double radius = 0.5 * shape.bounds().sizes().norm();
  const double around = 2 * kPi * radius / res + 4;
  return planar ? around : 6 * around * around;
}

// IK targets per obstacle point and draw: one per link point (and the CRS-F3's two upper-arm turns).
double linkPointCount(const robots::PlanarArm* planar, const robots::DhArm* dh, double res) {
  if (planar) {
    double n = 1;
    for (int link = 1; link < planar->dof(); ++link) n += steps(planar->lengths()[link], res);
    return n;
  }
  const auto& spec = dh->spec();
  return 2 + steps(std::abs(spec.rows.size() > 3 ? spec.rows[3].d : spec.flange.d), res);
}

// The IK solvers return angles in (-pi, pi]; a joint whose limits lie elsewhere (e.g. [0, 2 pi])
// reaches the same pose at q + 2 pi k. Moves each joint outside its limits, or with a range wider than a
// turn, to such a copy within its limits, drawn uniformly when the range holds several; false when a
// joint has none.
bool turnIntoLimits(Eigen::VectorXd& q, const robots::Robot& robot, cspace::Rng& rng) {
  for (int j = 0; j < q.size(); ++j) {
    const double lower = robot.lowerLimits()[j], upper = robot.upperLimits()[j];
    if (q[j] >= lower && q[j] <= upper && upper - lower <= 2 * kPi * (1 + 1e-12)) continue;
    const long first = static_cast<long>(std::ceil((lower - q[j]) / (2 * kPi)));
    const long last = static_cast<long>(std::floor((upper - q[j]) / (2 * kPi)));
    if (first > last) return false;
    const long k = first == last ? first : std::uniform_int_distribution<long>(first, last)(rng);
    q[j] += 2 * kPi * static_cast<double>(k);
  }
  return robot.withinLimits(q);  // rounding at a limit
}

}  // namespace

std::string IkSamplingOptions::validate() const {
  std::ostringstream err;
  if (!(link_resolution > 0)) err << "link_resolution must be positive, got " << link_resolution;
  else if (!(obstacle_resolution > 0)) err << "obstacle_resolution must be positive, got " << obstacle_resolution;
  else if (!(boundary_resolution > 0)) err << "boundary_resolution must be positive, got " << boundary_resolution;
  else if (free_joint_draws < 1) err << "free_joint_draws must be >= 1";
  else if (max_samples < 2) err << "max_samples must be >= 2";
  return err.str();
}

std::vector<Eigen::Vector3d> surfacePoints(const robots::Shape& shape, double res, bool planar) {
  std::vector<Eigen::Vector3d> local;
  const Eigen::Vector3d& d = shape.dims;
  const double z0 = -shape.pose.translation().z();  // the world plane z = 0 in the shape's frame
  if (planar && shape.kind == robots::ShapeKind::kBox) {
    // Outline of the cross-section with z = 0 (boxes standing upright: local z along world z).
    const Eigen::Vector2d h = 0.5 * d.head<2>();
    const Eigen::Vector2d corners[5] = {{-h.x(), -h.y()}, {h.x(), -h.y()}, {h.x(), h.y()}, {-h.x(), h.y()}, {-h.x(), -h.y()}};
    for (int side = 0; side < 4; ++side) {
      const Eigen::Vector2d from = corners[side], to = corners[side + 1];
      const int n = steps((to - from).norm(), res);
      for (int i = 0; i < n; ++i) {
        const Eigen::Vector2d p = from + (to - from) * (static_cast<double>(i) / n);
        local.emplace_back(p.x(), p.y(), z0);
      }
    }
  } else if (planar) {  // spheres, upright cylinders and capsules: a circle
    const double r = d.x();
    const int n = steps(2 * kPi * r, res);
    for (int i = 0; i < n; ++i)
      local.emplace_back(r * std::cos(2 * kPi * i / n), r * std::sin(2 * kPi * i / n), z0);
  } else if (shape.kind == robots::ShapeKind::kBox) {
    boxSurface(d, res, local);
  } else {
    // Spheres, cylinders and capsules: rings along the local z axis, walking the profile.
    const double r = d.x(), length = shape.kind == robots::ShapeKind::kSphere ? 0.0 : d.y();
    const bool caps = shape.kind != robots::ShapeKind::kCylinder;
    const double total = length + (caps ? kPi * r : 0.0);
    const int rings = steps(total, res);
    for (int k = 0; k <= rings; ++k) {
      const double arc = total * k / rings;
      double z = -0.5 * length + arc, radius = r;
      if (caps && arc < 0.5 * kPi * r) {
        z = -0.5 * length - r * std::cos(arc / r), radius = r * std::sin(arc / r);
      } else if (caps && arc > 0.5 * kPi * r + length) {
        const double a = (arc - length) / r;
        z = 0.5 * length - r * std::cos(a), radius = r * std::sin(a);
      } else if (caps) {
        z = -0.5 * length + (arc - 0.5 * kPi * r);
      }
      const int n = radius > 1e-12 ? steps(2 * kPi * radius, res) : 1;
      for (int i = 0; i < n; ++i)
        local.emplace_back(radius * std::cos(2 * kPi * i / n), radius * std::sin(2 * kPi * i / n), z);
    }
  }
  std::vector<Eigen::Vector3d> world;
  world.reserve(local.size());
  for (const auto& p : local) world.push_back(shape.pose * p);
  if (planar)
    for (auto& p : world) p.z() = 0;
  return world;
}

namespace {

// Samples of the configuration-space boundary: a grid on each face of the joint-limit box.
void boundarySamples(const cspace::ConfigurationSpace& space, double res, cspace::Rng& rng, int budget,
                     std::vector<Eigen::VectorXd>& out) {
  const int n = space.dim();
  const Eigen::VectorXd range = space.upper() - space.lower();
  double per_face = 1;
  for (int j = 0; j < n; ++j) per_face *= steps(range[j], res) + 1;
  for (int face = 0; face < 2 * n; ++face) {
    const int axis = face / 2;
    const int count = std::min<double>(per_face / (steps(range[axis], res) + 1), budget / (2.0 * n));
    for (int c = 0; c < count; ++c) {
      Eigen::VectorXd q = space.sampleUniform(rng);  // random points: a grid in 5-6 dims is too big
      q[axis] = face % 2 ? space.upper()[axis] : space.lower()[axis];
      out.push_back(q);
    }
  }
}

}  // namespace

IkSamples sampleObstaclesByIk(const cspace::ValidityChecker& checker,
                              const cspace::ConfigurationSpace& space,
                              const IkSamplingOptions& options, std::uint64_t seed,
                              const std::function<bool()>& stop) {
  const std::string err = options.validate();
  if (!err.empty()) throw std::invalid_argument("IK obstacle sampling: " + err);
  const robots::Robot& robot = checker.robot();
  const auto* planar = dynamic_cast<const robots::PlanarArm*>(&robot);
  const auto* dh = dynamic_cast<const robots::DhArm*>(&robot);
  // A DH arm other than the CRS-F3's elbow structure (the Panda) is bad input here, not a logic error.
  if (!planar && !(dh && dh->hasElbowStructure()))
    throw std::invalid_argument("IK obstacle sampling needs a planar arm or the CRS-F3 (robot '" +
                                robot.name() + "' has no closed-form IK here)");
  double link_res = options.link_resolution, obstacle_res = options.obstacle_resolution;
  const auto pairsAt = [&](double link, double obstacle) {
    double pairs = 0;
    for (const auto& o : checker.environment().obstacles()) pairs += surfacePointBound(o.shape, obstacle, planar);
    return pairs * options.free_joint_draws * linkPointCount(planar, dh, link);
  };
  for (int coarser = 0; coarser < 64 && pairsAt(link_res, obstacle_res) > IkSamplingOptions::kMaxPairs; ++coarser)
    link_res *= 1.5, obstacle_res *= 1.5;
  if (const double pairs = pairsAt(link_res, obstacle_res); pairs > IkSamplingOptions::kMaxPairs)
    throw std::invalid_argument("IK obstacle sampling: " + std::to_string(static_cast<long>(pairs)) +
                                " link-obstacle pairs at any resolution (obstacles x free_joint_draws), more than " +
                                std::to_string(static_cast<long>(IkSamplingOptions::kMaxPairs)));
  cspace::Rng rng(seed);
  // Algorithm R (Vitter 1985): a uniform subset of max_samples of all configurations found, in
  // memory that does not grow with how many there are; kept in the order they were found.
  struct Kept {
    long order;
    int region;
    Eigen::VectorXd q;
  };
  std::vector<Kept> kept;
  long found = 0;
  auto take = [&](const Eigen::VectorXd& q, int region) {
    if (found < options.max_samples) {
      kept.push_back({found, region, q});
    } else if (const long j = std::uniform_int_distribution<long>(0, found)(rng); j < options.max_samples) {
      kept[j] = {found, region, q};
    }
    ++found;
  };
  auto keep = [&](const std::vector<Eigen::VectorXd>& solutions, int region) {
    for (Eigen::VectorXd q : solutions)
      if (turnIntoLimits(q, robot, rng)) take(q, region);
  };
  Eigen::VectorXd free_joints(robot.dof());
  for (const auto& obstacle : checker.environment().obstacles()) {
    for (const Eigen::Vector3d& o : surfacePoints(obstacle.shape, obstacle_res, planar)) {
      if (stop && stop()) {
        IkSamples none;
        none.stopped = true;
        return none;
      }
      for (int draw = 0; draw < options.free_joint_draws; ++draw) {
        space.sampleUniform(rng, free_joints);
        if (planar) {
          const Eigen::Vector2d target = o.head<2>();
          const double s0 = (target - planar->base()).norm();  // link 1 touches o only here
          if (s0 > 0 && s0 <= planar->lengths()[0])
            keep(planar->solvePointOnLink(0, s0, target, free_joints), obstacle.id);
          for (int link = 1; link < robot.dof(); ++link) {
            const double length = planar->lengths()[link];
            const int n = steps(length, link_res);
            for (int i = 1; i <= n; ++i)
              keep(planar->solvePointOnLink(link, length * i / n, target, free_joints), obstacle.id);
          }
          continue;
        }
        // CRS-F3: the upper arm touches o at the distance of o from the shoulder (per base
        // orientation); the forearm at every link point. The short shoulder offset is not sampled.
        const auto& spec = dh->spec();
        const double forearm = std::abs(spec.rows.size() > 3 ? spec.rows[3].d : spec.flange.d);
        const double upper_arm = spec.rows[2].a;
        for (double turn : {0.0, kPi}) {
          Eigen::VectorXd q = free_joints;
          q[0] = std::remainder(std::atan2(o.y() - spec.base.translation().y(),
                                           o.x() - spec.base.translation().x()) + turn - spec.rows[0].offset,
                                2 * kPi);
          const double s = (o - dh->pointOnLinkFirstThree(q, 1, spec.rows[1].a)).norm();
          if (s > 0 && s <= upper_arm) keep(dh->solvePointOnLinkFirstThree(2, s, o, free_joints), obstacle.id);
        }
        const int n = steps(forearm, link_res);
        for (int i = 1; i <= n; ++i)
          keep(dh->solvePointOnLinkFirstThree(3, forearm * i / n, o, free_joints), obstacle.id);
      }
    }
  }
  // The joint limits bound the free space too (ch. 2.2.1); they get at most a third of the budget.
  std::vector<Eigen::VectorXd> boundary;
  boundarySamples(space, options.boundary_resolution, rng, options.max_samples / 3, boundary);
  for (const auto& q : boundary) take(q, kBoundaryRegion);

  std::sort(kept.begin(), kept.end(), [](const Kept& a, const Kept& b) { return a.order < b.order; });
  IkSamples samples;
  samples.points.resize(robot.dof(), static_cast<Eigen::Index>(kept.size()));
  for (size_t i = 0; i < kept.size(); ++i) {
    samples.points.col(static_cast<Eigen::Index>(i)) = kept[i].q;
    samples.regions.push_back(kept[i].region);
  }
  return samples;
}

}  // namespace svmp::planners
