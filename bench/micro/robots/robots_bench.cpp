// Forward kinematics per robot (link poses of one random configuration per iteration).
#include <benchmark/benchmark.h>

#include <memory>
#include <numbers>
#include <random>

#include "robots/dh_arm.hpp"
#include "robots/planar_arm.hpp"
#include "robots/point_robot.hpp"

namespace {

using svmp::robots::Robot;
constexpr double kPi = std::numbers::pi;

std::unique_ptr<Robot> planar(int links) {
  return std::make_unique<svmp::robots::PlanarArm>(
      std::vector<double>(links, 1.0), std::vector<double>(links, 0.1),
      Eigen::VectorXd::Constant(links, -kPi), Eigen::VectorXd::Constant(links, kPi));
}

std::unique_ptr<Robot> makeRobot(const std::string& name) {
  if (name == "point2d")
    return std::make_unique<svmp::robots::PointRobot>(Eigen::Vector2d(0, 0), Eigen::Vector2d(10, 10));
  if (name == "planar5") return planar(5);
  if (name == "planar6") return planar(6);
  if (name == "crs_f3") return std::make_unique<svmp::robots::DhArm>(svmp::robots::crsF3Spec(6));
  return std::make_unique<svmp::robots::DhArm>(svmp::robots::pandaSpec());
}

Eigen::MatrixXd randomConfigurations(const Robot& robot, int n) {
  std::mt19937_64 rng(1);
  Eigen::MatrixXd q(robot.dof(), n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < robot.dof(); ++i)
      q(i, j) = std::uniform_real_distribution<double>(robot.lowerLimits()[i], robot.upperLimits()[i])(rng);
  return q;
}

void BM_ForwardKinematics(benchmark::State& state, const std::string& name) {
  const auto robot = makeRobot(name);
  const Eigen::MatrixXd q = randomConfigurations(*robot, 1024);
  svmp::robots::Poses poses;
  int i = 0;
  for (auto _ : state) {
    robot->linkPoses(q.col(i++ & 1023), poses);
    benchmark::DoNotOptimize(poses.data());
  }
  state.SetItemsProcessed(state.iterations());
}

void BM_ControlPoints(benchmark::State& state, const std::string& name) {
  const auto robot = makeRobot(name);
  const Eigen::MatrixXd q = randomConfigurations(*robot, 1024);
  Eigen::Matrix3Xd points;
  int i = 0;
  for (auto _ : state) {
    robot->controlPoints(q.col(i++ & 1023), points);
    benchmark::DoNotOptimize(points.data());
  }
  state.SetItemsProcessed(state.iterations());
}

}  // namespace

BENCHMARK_CAPTURE(BM_ForwardKinematics, point2d, "point2d");
BENCHMARK_CAPTURE(BM_ForwardKinematics, planar5, "planar5");
BENCHMARK_CAPTURE(BM_ForwardKinematics, planar6, "planar6");
BENCHMARK_CAPTURE(BM_ForwardKinematics, crs_f3, "crs_f3");
BENCHMARK_CAPTURE(BM_ForwardKinematics, panda, "panda");
BENCHMARK_CAPTURE(BM_ControlPoints, planar6, "planar6");
BENCHMARK_CAPTURE(BM_ControlPoints, panda, "panda");

BENCHMARK_MAIN();
