#include "bench/experiments/fastron/collision_experiment.hpp"

#include <chrono>
#include <iomanip>
#include <ostream>
#include <sstream>
#include <stdexcept>

#include "bench/experiments/output_text.hpp"

namespace svmp::experiments::fastron {
namespace {

using Clock = std::chrono::steady_clock;
double usSince(Clock::time_point t0) { return std::chrono::duration<double, std::micro>(Clock::now() - t0).count(); }

constexpr int kSegmentLength = 64;  // configurations per batched motion check

struct TestSet {
  std::vector<Eigen::VectorXd> qs;
  std::vector<bool> colliding;
  Eigen::MatrixXd segments;  // kSegmentLength columns per segment, straight between test configurations
  double fcl_us = 0, fcl_batch_us = 0;  // per configuration
};

Eigen::VectorXd uniform(const robots::Robot& robot, std::mt19937_64& rng) {
  Eigen::VectorXd q(robot.dof());
  for (int k = 0; k < q.size(); ++k)
    q[k] = std::uniform_real_distribution<double>(robot.lowerLimits()[k], robot.upperLimits()[k])(rng);
  return q;
}

// Labels by FCL, timing its single queries on the same configurations the proxies answer.
TestSet makeTestSet(const robots::Robot& robot, const cspace::ValidityChecker& exact, int n, std::mt19937_64& rng) {
  TestSet t;
  for (int i = 0; i < n; ++i) t.qs.push_back(uniform(robot, rng));
  t.colliding.resize(n);
  auto t0 = Clock::now();
  for (int i = 0; i < n; ++i) t.colliding[i] = exact.check(t.qs[i]) != cspace::kFree;
  t.fcl_us = usSince(t0) / n;
  const int segments = std::max(1, n / kSegmentLength);
  t.segments.resize(robot.dof(), static_cast<Eigen::Index>(segments) * kSegmentLength);
  for (int s = 0; s < segments; ++s) {
    const Eigen::VectorXd& a = t.qs[s];
    const Eigen::VectorXd& b = t.qs[(s + segments) % n];
    // Short segments, as a planner checks: 1/8 of the way from a to b.
    for (int i = 0; i < kSegmentLength; ++i)
      t.segments.col(s * kSegmentLength + i) = a + (b - a) * (0.125 * i / (kSegmentLength - 1));
  }
  t0 = Clock::now();
  for (Eigen::Index c = 0; c < t.segments.cols(); ++c) exact.check(t.segments.col(c));  // counted: not elided
  t.fcl_batch_us = usSince(t0) / t.segments.cols();
  return t;
}

void evaluate(const cspace::FastronChecker& proxy, const TestSet& t, MethodSamples& m) {
  const int n = static_cast<int>(t.qs.size());
  std::vector<int> predicted(n);
  auto t0 = Clock::now();
  for (int i = 0; i < n; ++i) predicted[i] = proxy.check(t.qs[i]);
  m.query_us.push_back(usSince(t0) / n);
  int tp = 0, tn = 0, pos = 0;
  for (int i = 0; i < n; ++i) {
    const bool hit = predicted[i] != cspace::kFree;
    pos += t.colliding[i];
    tp += hit && t.colliding[i];
    tn += !hit && !t.colliding[i];
  }
  m.accuracy.push_back(double(tp + tn) / n);
  if (pos > 0) m.tpr.push_back(double(tp) / pos);  // undefined without positives: left out
  if (n - pos > 0) m.tnr.push_back(double(tn) / (n - pos));
  m.support.push_back(proxy.model().size());
  std::vector<int> out;
  t0 = Clock::now();
  for (Eigen::Index c = 0; c < t.segments.cols(); c += kSegmentLength)
    proxy.checkBatch(t.segments.middleCols(c, kSegmentLength), out);
  m.batch_us.push_back(usSince(t0) / t.segments.cols());
}

void recordFcl(const TestSet& t, MethodSamples& m) {
  m.accuracy.push_back(1), m.tpr.push_back(1), m.tnr.push_back(1);
  m.query_us.push_back(t.fcl_us);
  m.batch_us.push_back(t.fcl_batch_us);
}

std::string row(const std::string& name, const MethodSamples& m, bool proxy) {
  std::ostringstream o;
  auto ms = [](const std::vector<double>& v, int p, double scale = 1) {
    std::vector<double> s = v;
    for (double& x : s) x *= scale;
    return meanStd(statsOf(s), p);
  };
  o << pad(name, 12) << pad(ms(m.accuracy, 1, 100), 13) << pad(ms(m.tpr, 1, 100), 13) << pad(ms(m.tnr, 1, 100), 13)
    << pad(ms(m.query_us, 3), 16) << pad(ms(m.batch_us, 3), 16)
    << pad(proxy ? ms(m.support, 0) : "-", 14) << pad(proxy ? ms(m.update_ms, 2) : "-", 14)
    << pad(proxy ? ms(m.initial_label_ms, 1) + " + " + ms(m.initial_learn_ms, 1) : "-", 22) << "\n";
  return o.str();
}

std::string methodJson(const MethodSamples& m) {
  std::ostringstream o;
  o << "{\"accuracy\": " << jsonStats(statsOf(m.accuracy)) << ", \"tpr\": " << jsonStats(statsOf(m.tpr))
    << ", \"tnr\": " << jsonStats(statsOf(m.tnr)) << ", \"query_us\": " << jsonStats(statsOf(m.query_us))
    << ", \"batch_us_per_configuration\": " << jsonStats(statsOf(m.batch_us))
    << ", \"support_points\": " << jsonStats(statsOf(m.support)) << ", \"update_ms\": " << jsonStats(statsOf(m.update_ms))
    << ", \"update_label_ms\": " << jsonStats(statsOf(m.update_label_ms))
    << ", \"initial_label_ms\": " << jsonStats(statsOf(m.initial_label_ms))
    << ", \"initial_learn_ms\": " << jsonStats(statsOf(m.initial_learn_ms))
    << ", \"converged\": " << jsonStats(statsOf(m.converged)) << ", \"steps\": " << jsonStats(statsOf(m.steps)) << "}";
  return o.str();
}

std::shared_ptr<const cspace::Environment> randomBoxes(int count, const MovingBoxOptions& box, std::mt19937_64& rng) {
  std::vector<cspace::Obstacle> obstacles;
  for (int i = 0; i < count; ++i) {
    MovingBoxOptions small = box;
    small.max_side = box.min_side + (box.max_side - box.min_side) / 2;  // many obstacles: smaller ones
    const MovingBox b(small, rng);
    cspace::Obstacle o = b.environment()->obstacles().front();
    o.name = "box_" + std::to_string(i + 1);
    obstacles.push_back(o);
  }
  return std::make_shared<const cspace::Environment>(obstacles);
}

}  // namespace

CollisionResults runCollisionExperiment(const cspace::Scenario& scenario, const CollisionExperimentOptions& options,
                                        std::ostream& log) {
  CollisionResults r;
  r.fk.name = "fastron-fk", r.rbf.name = "fastron-rbf", r.fcl.name = "fcl";
  const robots::Robot& robot = *scenario.robot;
  std::vector<double> fractions;
  for (int trial = 0; trial < options.trials; ++trial) {
    std::mt19937_64 rng(options.seed + 1000003ULL * trial);
    MovingBox box(options.box, rng);
    cspace::FastronChecker fk(scenario.robot, options.fk), rbf(scenario.robot, options.rbf);
    for (int move = 0; move <= options.moves; ++move) {
      if (move > 0) box.move(rng);
      const auto exact = box.checker(scenario);
      const std::uint64_t seed = rng();
      for (auto [proxy, m] : {std::pair{&fk, &r.fk}, std::pair{&rbf, &r.rbf}}) {
        const cspace::FastronLearnStats s = move == 0 ? proxy->train(*exact, seed) : proxy->update(*exact, seed);
        if (move == 0) {
          m->initial_label_ms.push_back(s.label_ms);
          m->initial_learn_ms.push_back(s.learn_ms);
        } else {
          m->update_ms.push_back(s.label_ms + s.learn_ms);
          m->update_label_ms.push_back(s.label_ms);
        }
        m->converged.push_back(s.train.converged);
        m->steps.push_back(s.train.steps);
      }
      const TestSet test = makeTestSet(robot, *exact, options.test_samples, rng);
      fractions.push_back(std::count(test.colliding.begin(), test.colliding.end(), true) / double(test.qs.size()));
      evaluate(fk, test, r.fk);
      evaluate(rbf, test, r.rbf);
      recordFcl(test, r.fcl);
    }
    log << "trial " << trial + 1 << "/" << options.trials << ": fk accuracy " << std::fixed << std::setprecision(3)
        << r.fk.accuracy.back() << " (" << fk.model().size() << " support points), rbf " << r.rbf.accuracy.back()
        << " (" << rbf.model().size() << "); trainings converged: fk " << statsOf(r.fk.converged).mean << ", rbf "
        << statsOf(r.rbf.converged).mean << "; steps fk " << statsOf(r.fk.steps).mean << ", rbf " << statsOf(r.rbf.steps).mean << "\n";
  }
  r.collision_fraction = statsOf(fractions).mean;
  if (r.fk.tpr.empty() || r.fk.tnr.empty())
    throw std::runtime_error(std::string("no test set had a configuration ") +
                             (r.fk.tpr.empty() ? "in collision" : "free") +
                             ": the moving box (a ring 0.35-0.75 m round the base, for an arm of the Panda's size) "
                             "never met this scenario's robot, so TPR and TNR are undefined");

  for (int count : options.obstacle_counts) {
    ObstacleCountRow row;
    row.obstacles = count;
    std::vector<double> f, fcl, fku, rbfu, fks, rbfs, fka, rbfa;
    for (int trial = 0; trial < options.obstacle_trials; ++trial) {
      std::mt19937_64 rng(options.seed + 7919ULL * count + 104729ULL * trial);
      const cspace::CollisionChecker exact(scenario.robot, randomBoxes(count, options.box, rng), scenario.self_collision);
      cspace::FastronChecker fk(scenario.robot, options.fk), rbf(scenario.robot, options.rbf);
      fk.train(exact, rng());
      rbf.train(exact, rng());
      const TestSet test = makeTestSet(robot, exact, options.test_samples, rng);
      MethodSamples a, b;
      evaluate(fk, test, a);
      evaluate(rbf, test, b);
      f.push_back(std::count(test.colliding.begin(), test.colliding.end(), true) / double(test.qs.size()));
      fcl.push_back(test.fcl_us), fku.push_back(a.query_us[0]), rbfu.push_back(b.query_us[0]);
      fks.push_back(a.support[0]), rbfs.push_back(b.support[0]), fka.push_back(a.accuracy[0]), rbfa.push_back(b.accuracy[0]);
    }
    row.collision_fraction = statsOf(f).mean;
    row.fcl_us = statsOf(fcl).median, row.fk_us = statsOf(fku).median, row.rbf_us = statsOf(rbfu).median;
    row.fk_support = statsOf(fks).mean, row.rbf_support = statsOf(rbfs).mean;
    row.fk_accuracy = statsOf(fka).mean, row.rbf_accuracy = statsOf(rbfa).mean;
    r.by_obstacles.push_back(row);
    log << count << " obstacles: fcl " << row.fcl_us << " us, fk " << row.fk_us << " us, rbf " << row.rbf_us << " us\n";
  }
  return r;
}

void printCollisionTables(const CollisionResults& r, std::ostream& out) {
  out << "Table I / Fig 4: one moving box, " << r.fk.accuracy.size() << " evaluations (trials x (moves + 1)); "
      << std::fixed << std::setprecision(1) << 100 * r.collision_fraction
      << "% of test configurations in collision; mean ± std\n";
  out << pad("method", 12) << pad("accuracy %", 13) << pad("TPR %", 13) << pad("TNR %", 13) << pad("query us", 16)
      << pad("batch us/conf", 16) << pad("support pts", 14) << pad("update ms", 14)
      << pad("initial ms (label + learn)", 22) << "\n";
  out << row("fastron-fk", r.fk, true) << row("fastron-rbf", r.rbf, true) << row("fcl", r.fcl, false);
  if (r.by_obstacles.empty()) return;
  out << "\nFig 7: query time (median us) against the number of obstacles\n";
  out << pad("obstacles", 11) << pad("in collision %", 16) << pad("fcl", 9) << pad("fastron-fk", 12)
      << pad("fastron-rbf", 13) << pad("fk support", 12) << pad("rbf support", 13) << pad("fk acc %", 10) << "rbf acc %\n";
  for (const auto& row : r.by_obstacles) {
    std::ostringstream o;
    o << std::fixed << std::setprecision(3) << pad(std::to_string(row.obstacles), 11)
      << pad(std::to_string(static_cast<int>(100 * row.collision_fraction + 0.5)), 16);
    auto num = [](double x, int p) { std::ostringstream s; s << std::fixed << std::setprecision(p) << x; return s.str(); };
    o << pad(num(row.fcl_us, 3), 9) << pad(num(row.fk_us, 3), 12) << pad(num(row.rbf_us, 3), 13)
      << pad(num(row.fk_support, 0), 12) << pad(num(row.rbf_support, 0), 13) << pad(num(100 * row.fk_accuracy, 1), 10)
      << num(100 * row.rbf_accuracy, 1) << "\n";
    out << o.str();
  }
}

std::string collisionJson(const CollisionResults& r) {
  std::ostringstream o;
  o << std::setprecision(10) << "{\"collision_fraction\": " << r.collision_fraction << ", \"fastron_fk\": " << methodJson(r.fk)
    << ", \"fastron_rbf\": " << methodJson(r.rbf) << ", \"fcl\": " << methodJson(r.fcl) << ", \"by_obstacles\": [";
  for (size_t i = 0; i < r.by_obstacles.size(); ++i) {
    const auto& row = r.by_obstacles[i];
    o << (i ? ", " : "") << "{\"obstacles\": " << row.obstacles << ", \"collision_fraction\": " << row.collision_fraction
      << ", \"fcl_us\": " << row.fcl_us << ", \"fastron_fk_us\": " << row.fk_us << ", \"fastron_rbf_us\": " << row.rbf_us
      << ", \"fastron_fk_support\": " << row.fk_support << ", \"fastron_rbf_support\": " << row.rbf_support
      << ", \"fastron_fk_accuracy\": " << row.fk_accuracy << ", \"fastron_rbf_accuracy\": " << row.rbf_accuracy << "}";
  }
  o << "]}";
  return o.str();
}

}  // namespace svmp::experiments::fastron
