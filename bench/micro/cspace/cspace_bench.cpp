// Collision checks per robot against a few obstacles (thesis Fig 4.4 style for the planar arms),
// clearance and straight-line motion validation. Random configurations within the joint limits.
#include <benchmark/benchmark.h>
#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>

#include <memory>
#include <numbers>
#include <random>

#include "cspace/collision_checker.hpp"
#include "cspace/certified_motion_validator.hpp"
#include "cspace/convex_distance.hpp"
#include "cspace/motion_validator.hpp"
#include "cspace/obstacle_grid.hpp"
#include "robots/dh_arm.hpp"
#include "robots/planar_arm.hpp"
#include "robots/point_robot.hpp"

namespace {

using svmp::cspace::CollisionChecker;
using svmp::cspace::Environment;
using svmp::cspace::Obstacle;
using svmp::robots::Shape;
constexpr double kPi = std::numbers::pi;

Obstacle box(Eigen::Vector3d sides, Eigen::Vector3d centre) {
  Obstacle o;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = centre;
  o.shape = Shape::box(sides, pose);
  return o;
}

struct World {
  std::shared_ptr<const svmp::robots::Robot> robot;
  std::shared_ptr<const Environment> env;
};

// An arm among 60 cubes of 6-8 cm around its base (as bench/unseen/*_clutter*): the broadphase's case.
std::vector<Obstacle> clutter(int count) {
  std::mt19937_64 rng(6);
  std::uniform_real_distribution<double> unit(0, 1);
  std::vector<Obstacle> boxes;
  while (static_cast<int>(boxes.size()) < count) {
    const double r = 0.3 + 0.4 * unit(rng), a = 2 * kPi * unit(rng), side = 0.06 + 0.02 * unit(rng);
    boxes.push_back(box(Eigen::Vector3d::Constant(side), {r * std::cos(a), r * std::sin(a), 0.05 + 0.85 * unit(rng)}));
  }
  return boxes;
}

World makeWorld(const std::string& name) {
  if (name == "panda_clutter")
    return {std::make_shared<svmp::robots::DhArm>(svmp::robots::pandaSpec()),
            std::make_shared<Environment>(clutter(60))};
  if (name == "point2d") {
    return {std::make_shared<svmp::robots::PointRobot>(Eigen::Vector2d(0, 0), Eigen::Vector2d(10, 10)),
            std::make_shared<Environment>(std::vector<Obstacle>{
                box({4, 6, 1}, {5, 3, 0}), box({4, 3.7, 1}, {5, 8.15, 0})})};
  }
  if (name == "planar5" || name == "planar6") {
    // Fig 4.4 style: unit links around the base, three blocks in reach.
    const int n = name == "planar5" ? 5 : 6;
    return {std::make_shared<svmp::robots::PlanarArm>(
                std::vector<double>(n, 1.0), std::vector<double>(n, 0.1),
                Eigen::VectorXd::Constant(n, -kPi), Eigen::VectorXd::Constant(n, kPi)),
            std::make_shared<Environment>(std::vector<Obstacle>{
                box({1, 1, 1}, {3, 1, 0}), box({0.5, 2, 1}, {-2, 2, 0}), box({2, 0.5, 1}, {0, -3, 0})})};
  }
  const bool crs = name == "crs_f3";
  return {std::make_shared<svmp::robots::DhArm>(crs ? svmp::robots::crsF3Spec(6) : svmp::robots::pandaSpec()),
          std::make_shared<Environment>(std::vector<Obstacle>{
              box({1, 1, 0.05}, {0.4, 0, -0.05}),  // table
              box({0.1, 0.4, 0.4}, {0.45, 0.3, 0.3}), box({0.2, 0.2, 0.2}, {-0.3, -0.3, 0.6})})};
}

Eigen::MatrixXd randomConfigurations(const svmp::robots::Robot& robot, int n) {
  std::mt19937_64 rng(1);
  Eigen::MatrixXd q(robot.dof(), n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < robot.dof(); ++i)
      q(i, j) = std::uniform_real_distribution<double>(robot.lowerLimits()[i], robot.upperLimits()[i])(rng);
  return q;
}

void BM_CollisionCheck(benchmark::State& state, const std::string& name) {
  const World world = makeWorld(name);
  const CollisionChecker checker(world.robot, world.env);
  const Eigen::MatrixXd q = randomConfigurations(*world.robot, 1024);
  int i = 0, hits = 0;
  for (auto _ : state) hits += checker.check(q.col(i++ & 1023)) != svmp::cspace::kFree;
  state.SetItemsProcessed(state.iterations());
  state.counters["colliding"] = static_cast<double>(hits) / state.iterations();
}

void BM_Clearance(benchmark::State& state, const std::string& name) {
  const World world = makeWorld(name);
  const CollisionChecker checker(world.robot, world.env);
  const Eigen::MatrixXd q = randomConfigurations(*world.robot, 1024);
  int i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(checker.clearance(q.col(i++ & 1023)));
  state.SetItemsProcessed(state.iterations());
}

// Random segments of metric length ~0.5 at resolution 0.01 (about 50 checks when free), sampled
// (the thesis' local planner) or certified (FCL free distance and the displacement bound).
template <class Validator>
void BM_MotionValidator(benchmark::State& state, const std::string& name) {
  const World world = makeWorld(name);
  const CollisionChecker checker(world.robot, world.env);
  const svmp::cspace::ConfigurationSpace space(world.robot->lowerLimits(), world.robot->upperLimits(),
                                               Eigen::VectorXd::Ones(world.robot->dof()));
  const Validator validator(checker, space, 0.01);
  const Eigen::MatrixXd a = randomConfigurations(*world.robot, 256);
  Eigen::MatrixXd b(a.rows(), a.cols());
  std::mt19937_64 rng(2);
  for (int j = 0; j < a.cols(); ++j) b.col(j) = space.steer(a.col(j), space.sampleUniform(rng), 0.5);
  int i = 0;
  for (auto _ : state) {
    const int j = i++ & 255;
    benchmark::DoNotOptimize(validator.isValid(a.col(j), b.col(j)));
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["checks_per_segment"] = static_cast<double>(checker.collisionChecks()) / state.iterations();
  state.counters["distances_per_segment"] = static_cast<double>(checker.distanceQueries()) / state.iterations();
}

void BM_SampledSegment(benchmark::State& state, const std::string& name) {
  BM_MotionValidator<svmp::cspace::DiscreteMotionValidator>(state, name);
}
void BM_CertifiedSegment(benchmark::State& state, const std::string& name) {
  BM_MotionValidator<svmp::cspace::CertifiedMotionValidator>(state, name);
}

// Link capsules against a board, as the checker and the certifier meet them: 256 capsules, random
// orientations, lowered onto the board until their gap is `gap` (10^-4..10^-1 m: the certifier's
// distances) or -2..2 cm (the checker's tests, half of them hits).
struct CapsulesOnABoard {
  Shape board = Shape::box(Eigen::Vector3d(0.8, 0.3, 0.02)), link = Shape::capsule(0.06, 0.2);
  std::shared_ptr<fcl::CollisionObjectd> board_object =
      std::make_shared<fcl::CollisionObjectd>(std::make_shared<fcl::Boxd>(0.8, 0.3, 0.02));
  std::vector<Eigen::Isometry3d> poses;
  std::vector<std::shared_ptr<fcl::CollisionObjectd>> links;

  explicit CapsulesOnABoard(bool touching) {
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> unit(-1, 1), exponent(-4, -1);
    while (poses.size() < 256) {
      Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
      pose.linear() = Eigen::Quaterniond(Eigen::Vector4d(unit(rng), unit(rng), unit(rng), unit(rng)).normalized())
                          .toRotationMatrix();
      pose.translation() = Eigen::Vector3d(0.3 * unit(rng), 0.1 * unit(rng), 1.0);
      const double lowest = pose.translation().z() - std::abs(pose.linear()(2, 2)) * 0.1 - 0.06;
      const double gap = touching ? 0.02 * unit(rng) : std::pow(10.0, exponent(rng));
      pose.translation().z() -= lowest - 0.01 - gap;
      poses.push_back(pose);
      links.push_back(std::make_shared<fcl::CollisionObjectd>(std::make_shared<fcl::Capsuled>(0.06, 0.2), pose));
    }
  }
};

// One distance query's inner step: FCL's distance (libccd GJK, nearest points) followed by the
// separating plane along its direction, which the checker ran until the sixteenth session, against
// our GJK alone on the capsule's segment (cspace/convex_distance.hpp).
void BM_CapsuleBoxDistance(benchmark::State& state, bool fcl_first) {
  const CapsulesOnABoard c(false);
  int i = 0;
  for (auto _ : state) {
    const int j = i++ & 255;
    double d;
    if (fcl_first) {
      fcl::DistanceRequestd request(true);
      fcl::DistanceResultd result;
      fcl::distance(c.links[j].get(), c.board_object.get(), request, result);
      d = svmp::cspace::distanceLowerBound(c.link, c.poses[j], c.board, Eigen::Isometry3d::Identity(),
                                            result.nearest_points[0] - result.nearest_points[1], 1e-3);
    } else {
      d = svmp::cspace::distanceLowerBound(c.link, c.poses[j], c.board, Eigen::Isometry3d::Identity(),
                                            c.poses[j].translation(), 1e-3);
    }
    benchmark::DoNotOptimize(d);
  }
  state.SetItemsProcessed(state.iterations());
}

// The checker's narrow phase on one pair: FCL's collide against our intersects.
void BM_CapsuleBoxCollide(benchmark::State& state, bool fcl) {
  const CapsulesOnABoard c(true);
  int i = 0, hits = 0;
  for (auto _ : state) {
    const int j = i++ & 255;
    if (fcl) {
      fcl::CollisionRequestd request;
      fcl::CollisionResultd result;
      hits += fcl::collide(c.links[j].get(), c.board_object.get(), request, result) > 0;
    } else {
      hits += svmp::cspace::intersects(c.link, c.poses[j], c.board, Eigen::Isometry3d::Identity()).value_or(false);
    }
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["hits"] = static_cast<double>(hits) / state.iterations();
}

}  // namespace

BENCHMARK_CAPTURE(BM_CapsuleBoxDistance, fcl_then_plane, true);
BENCHMARK_CAPTURE(BM_CapsuleBoxDistance, own_gjk, false);

// FCL's distance alone on the same pairs, as a user of FCL asks it (nearest points, its default
// tolerance): the rival of own_gjk, which stops within 1e-3 of the distance and gives a bound.
void BM_CapsuleBoxDistanceFcl(benchmark::State& state) {
  const CapsulesOnABoard c(false);
  int i = 0;
  for (auto _ : state) {
    fcl::DistanceRequestd request(true);
    fcl::DistanceResultd result;
    fcl::distance(c.links[i++ & 255].get(), c.board_object.get(), request, result);
    benchmark::DoNotOptimize(result.min_distance);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_CapsuleBoxDistanceFcl)->Name("BM_CapsuleBoxDistance/fcl");
BENCHMARK_CAPTURE(BM_CapsuleBoxCollide, fcl, true);
BENCHMARK_CAPTURE(BM_CapsuleBoxCollide, own_gjk, false);
BENCHMARK_CAPTURE(BM_CollisionCheck, point2d, "point2d");
BENCHMARK_CAPTURE(BM_CollisionCheck, planar5, "planar5");
BENCHMARK_CAPTURE(BM_CollisionCheck, planar6, "planar6");
BENCHMARK_CAPTURE(BM_CollisionCheck, crs_f3, "crs_f3");
BENCHMARK_CAPTURE(BM_CollisionCheck, panda, "panda");
BENCHMARK_CAPTURE(BM_CollisionCheck, panda_clutter, "panda_clutter");
BENCHMARK_CAPTURE(BM_Clearance, planar6, "planar6");
BENCHMARK_CAPTURE(BM_Clearance, panda, "panda");
BENCHMARK_CAPTURE(BM_SampledSegment, point2d, "point2d");
BENCHMARK_CAPTURE(BM_SampledSegment, planar6, "planar6");
BENCHMARK_CAPTURE(BM_SampledSegment, panda, "panda");
BENCHMARK_CAPTURE(BM_CertifiedSegment, point2d, "point2d");
BENCHMARK_CAPTURE(BM_CertifiedSegment, planar6, "planar6");
BENCHMARK_CAPTURE(BM_CertifiedSegment, panda, "panda");

// An FCL object whose world box is set from outside: FCL's computeAABB boxes a turned shape by a cube
// round its bounding sphere, and the broadphase pair below must query with the same boxes.
struct BoxedObject : fcl::CollisionObjectd {
  BoxedObject(const std::shared_ptr<fcl::CollisionGeometryd>& g, const Eigen::AlignedBox3d& box)
      : fcl::CollisionObjectd(g) {
    aabb = fcl::AABBd(box.min(), box.max());
  }
};

// The broadphase alone, FCL's dynamic AABB tree (the checker's until the twenty-first session) against
// our grid (cspace/obstacle_grid.hpp): the candidates of a link-sized box among 60 small cubes, the
// boxes placed where the Panda's parts are at random configurations. Both are asked with the same
// query boxes and count the same overlaps (`candidates` per query, equal on both: the grid's
// candidates are a superset, kept when their box overlaps).
void BM_Broadphase(benchmark::State& state, bool grid) {
  const auto obstacles = clutter(60);
  std::vector<Eigen::AlignedBox3d> boxes;
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> objects;
  fcl::DynamicAABBTreeCollisionManagerd manager;
  for (const auto& o : obstacles) {
    boxes.push_back(o.shape.boundsAt(o.shape.pose));
    objects.push_back(std::make_unique<fcl::CollisionObjectd>(
        std::make_shared<fcl::Boxd>(o.shape.dims.x(), o.shape.dims.y(), o.shape.dims.z()), o.shape.pose.linear(),
        o.shape.pose.translation()));
    objects.back()->computeAABB();
    manager.registerObject(objects.back().get());
  }
  manager.setup();
  const svmp::cspace::ObstacleGrid obstacle_grid(boxes);
  // Query boxes: the Panda's parts at 256 random configurations.
  const svmp::robots::DhArm panda(svmp::robots::pandaSpec());
  const Eigen::MatrixXd q = randomConfigurations(panda, 256);
  std::vector<Eigen::AlignedBox3d> queries;
  std::vector<std::unique_ptr<BoxedObject>> parts;
  svmp::robots::Poses poses;
  for (int j = 0; j < q.cols(); ++j) {
    panda.linkPoses(q.col(j), poses);
    for (int l = 0; l < panda.numLinks(); ++l)
      for (const Shape& s : panda.linkShapes(l)) {
        const Eigen::Isometry3d at = poses[l] * s.pose;
        queries.push_back(s.boundsAt(at));
        parts.push_back(std::make_unique<BoxedObject>(std::make_shared<fcl::Capsuled>(s.dims.x(), s.dims.y()),
                                                      queries.back()));
      }
  }
  long found = 0, i = 0;
  auto count = [](fcl::CollisionObjectd*, fcl::CollisionObjectd*, void* n) {
    ++*static_cast<long*>(n);
    return false;
  };
  for (auto _ : state) {
    const size_t k = static_cast<size_t>(i++) % queries.size();
    if (grid)
      obstacle_grid.forEachCandidate(queries[k], [&](int b) { found += boxes[b].intersects(queries[k]); });
    else
      manager.collide(parts[k].get(), &found, count);
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["candidates"] = static_cast<double>(found) / state.iterations();
}
BENCHMARK_CAPTURE(BM_Broadphase, fcl_tree, false);
BENCHMARK_CAPTURE(BM_Broadphase, grid, true);

BENCHMARK_MAIN();
