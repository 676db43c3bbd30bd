// Fastron proxy collision checking (Das & Yip 2019) against exact checking on the same
// configurations: single queries, batched motion checks (64 configurations of one segment at once) and
// a model update after the obstacle moved. Two exact rivals: `fcl`, our checker (FCL's primitives,
// decided by our GJK: what the planners use), and `fcllib`, FCL alone (its bounding boxes, then
// fcl::collide on each link part against the box, as a user of FCL would write it; the paper's
// baseline). Scenario:
// bench/scenarios/fastron_panda.yaml (Panda with a hand, one box, no self-collision); models trained
// on 5,000 labelled configurations with the defaults of svmp-fastron.
#include <benchmark/benchmark.h>
#include <fcl/narrowphase/collision.h>

#include <memory>
#include <random>
#include <stdexcept>

#include "cspace/collision_checker.hpp"
#include "cspace/fastron_checker.hpp"
#include "cspace/scenario/scenario.hpp"
#include "tests/cspace/fcl_geometry.hpp"

namespace {

using namespace svmp;

// FCL alone: one collision object per link part and per obstacle, placed by the robot's forward
// kinematics, each pair whose FCL bounding boxes overlap decided by fcl::collide (no self-collision:
// the scenario has none).
class FclLibraryChecker {
 public:
  explicit FclLibraryChecker(const cspace::Scenario& s) : robot_(*s.robot) {
    if (s.self_collision) throw std::invalid_argument("FclLibraryChecker: no self-collision pairs");
    for (int i = 0; i < robot_.numLinks(); ++i)
      for (const robots::Shape& shape : robot_.linkShapes(i))
        parts_.push_back({i, &shape, std::make_unique<fcl::CollisionObjectd>(cspace::test::fclGeometry(shape))});
    for (const auto& o : s.environment->obstacles()) {
      obstacles_.push_back(std::make_unique<fcl::CollisionObjectd>(cspace::test::fclGeometry(o.shape),
                                                                   o.shape.pose.linear(), o.shape.pose.translation()));
      obstacles_.back()->computeAABB();
    }
  }
  bool collides(const Eigen::Ref<const Eigen::VectorXd>& q) {
    if (!robot_.withinLimits(q)) return true;
    robot_.linkPoses(q, poses_);
    for (Part& p : parts_) {
      const Eigen::Isometry3d pose = poses_[p.link] * p.shape->pose;
      p.object->setTransform(pose.linear(), pose.translation());
      p.object->computeAABB();
      for (const auto& o : obstacles_) {
        if (!p.object->getAABB().overlap(o->getAABB())) continue;  // what a broadphase manager culls
        fcl::CollisionResultd result;
        if (fcl::collide(p.object.get(), o.get(), fcl::CollisionRequestd(), result) > 0) return true;
      }
    }
    return false;
  }

 private:
  struct Part {
    int link;
    const robots::Shape* shape;
    std::unique_ptr<fcl::CollisionObjectd> object;
  };
  const robots::Robot& robot_;
  std::vector<Part> parts_;
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> obstacles_;
  robots::Poses poses_;
};

struct Fixture {
  cspace::Scenario scenario = cspace::loadScenario(SVMP_SOURCE_DIR "/bench/scenarios/fastron_panda.yaml");
  cspace::CollisionChecker exact{scenario.robot, scenario.environment, scenario.self_collision};
  cspace::FastronChecker fk{scenario.robot, cspace::FastronCheckerOptions::defaults(cspace::FastronFeatures::kControlPoints)};
  cspace::FastronChecker rbf{scenario.robot, cspace::FastronCheckerOptions::defaults(cspace::FastronFeatures::kJoints)};
  Eigen::MatrixXd configurations, segments;  // 1024 uniform; 16 segments of 64
  Fixture() {
    fk.train(exact, 1);
    rbf.train(exact, 1);
    std::mt19937_64 rng(7);
    const auto& robot = *scenario.robot;
    configurations.resize(robot.dof(), 1024);
    for (int i = 0; i < 1024; ++i)
      for (int k = 0; k < robot.dof(); ++k)
        configurations(k, i) =
            std::uniform_real_distribution<double>(robot.lowerLimits()[k], robot.upperLimits()[k])(rng);
    segments.resize(robot.dof(), 1024);
    for (int s = 0; s < 16; ++s)
      for (int i = 0; i < 64; ++i)
        segments.col(s * 64 + i) =
            configurations.col(s) + (configurations.col(s + 16) - configurations.col(s)) * (0.125 * i / 63.0);
  }
  const cspace::ValidityChecker& checker(int which) const {
    return which == 0 ? static_cast<const cspace::ValidityChecker&>(exact) : which == 1 ? fk : rbf;
  }
};

Fixture& fixture() {
  static Fixture f;
  return f;
}

// FCL alone on the fixture's configurations; an error when it disagrees with our checker on one of
// them (then the two would not be doing the same work).
void BM_QueryFclLibrary(benchmark::State& state) {
  const auto& f = fixture();
  FclLibraryChecker fcl(f.scenario);
  for (int i = 0; i < 1024; ++i)
    if (fcl.collides(f.configurations.col(i)) != (f.exact.check(f.configurations.col(i)) != cspace::kFree)) {
      state.SkipWithError("FCL and our checker disagree on a configuration");
      return;
    }
  int i = 0, hits = 0;
  for (auto _ : state) hits += fcl.collides(f.configurations.col(i++ & 1023));
  benchmark::DoNotOptimize(hits);
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_QueryFclLibrary)->Name("BM_Query/fcllib/panda");

void BM_MotionBatchFclLibrary(benchmark::State& state) {
  const auto& f = fixture();
  FclLibraryChecker fcl(f.scenario);
  int s = 0, hits = 0;
  for (auto _ : state) {
    const auto seg = f.segments.middleCols((s++ & 15) * 64, 64);
    for (int i = 0; i < 64; ++i) hits += fcl.collides(seg.col(i));
  }
  benchmark::DoNotOptimize(hits);
  state.SetItemsProcessed(state.iterations() * 64);
}
BENCHMARK(BM_MotionBatchFclLibrary)->Name("BM_MotionBatch/fcllib/panda");

// which: 0 our exact checker, 1 Fastron FK, 2 Fastron RBF. Names BM_X/{fcl,fcllib,fk,rbf}/panda pair
// for scripts/bench_ratios.
void BM_Query(benchmark::State& state, int which) {
  const auto& f = fixture();
  const auto& checker = f.checker(which);
  int i = 0, hits = 0;
  for (auto _ : state) hits += checker.check(f.configurations.col(i++ & 1023)) != cspace::kFree;
  benchmark::DoNotOptimize(hits);
  state.SetItemsProcessed(state.iterations());
  if (which > 0) state.counters["support"] = static_cast<const cspace::FastronChecker&>(checker).model().size();
}
BENCHMARK_CAPTURE(BM_Query, fcl/panda, 0);
BENCHMARK_CAPTURE(BM_Query, fk/panda, 1);
BENCHMARK_CAPTURE(BM_Query, rbf/panda, 2);

// All 64 configurations of one segment (no early exit, so every checker does the same work).
void BM_MotionBatch(benchmark::State& state, int which) {
  const auto& f = fixture();
  int s = 0, hits = 0;
  std::vector<int> out;
  for (auto _ : state) {
    const auto seg = f.segments.middleCols((s++ & 15) * 64, 64);
    if (which == 0) {
      for (int i = 0; i < 64; ++i) hits += f.exact.check(seg.col(i)) != cspace::kFree;
    } else {
      (which == 1 ? f.fk : f.rbf).checkBatch(seg, out);
      hits += out[0];
    }
  }
  benchmark::DoNotOptimize(hits);
  state.SetItemsProcessed(state.iterations() * 64);
}
BENCHMARK_CAPTURE(BM_MotionBatch, fcl/panda, 0);
BENCHMARK_CAPTURE(BM_MotionBatch, fk/panda, 1);
BENCHMARK_CAPTURE(BM_MotionBatch, rbf/panda, 2);

// Active learning and a warm update after the box moved 5 cm (labelling by FCL included), each from a
// freshly trained model (not timed), so every iteration measures the same first update.
void BM_Update(benchmark::State& state, cspace::FastronFeatures features) {
  const auto& f = fixture();
  std::vector<cspace::Obstacle> obstacles = f.scenario.environment->obstacles();
  obstacles.front().shape.pose.translation().x() += 0.05;
  const cspace::CollisionChecker moved(f.scenario.robot, std::make_shared<const cspace::Environment>(obstacles),
                                       f.scenario.self_collision);
  std::uint64_t seed = 11;
  for (auto _ : state) {
    state.PauseTiming();
    cspace::FastronChecker model(f.scenario.robot, cspace::FastronCheckerOptions::defaults(features));
    model.train(f.exact, seed);
    state.ResumeTiming();
    const auto s = model.update(moved, ++seed);
    state.counters["support"] = s.train.support;
  }
}
BENCHMARK_CAPTURE(BM_Update, fk/panda, cspace::FastronFeatures::kControlPoints)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Update, rbf/panda, cspace::FastronFeatures::kJoints)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
