#pragma once
// Das & Yip 2019, sec. IV-A: Fastron FK and Fastron RBF against the exact FCL checker under a moving
// obstacle (Table I, Fig 4), and query time against the number of obstacles (Fig 7).
// Protocol: per trial one box of random size (moving_box.hpp); the models are trained on
// initial_samples labelled uniform configurations, then the box moves `moves` times and the models are
// updated after each move (active learning, warm start). After the initial training and after every
// update, test_samples held-out uniform configurations labelled by FCL give accuracy, TPR (collision
// predicted as collision) and TNR; the same configurations time single queries of every checker, and
// segments of 64 interpolated configurations time batched motion checks.
#include <iosfwd>
#include <string>
#include <vector>

#include "bench/experiments/fastron/moving_box.hpp"
#include "cspace/fastron_checker.hpp"

namespace svmp::experiments::fastron {

struct CollisionExperimentOptions {
  int trials = 50, moves = 30, test_samples = 2000;
  std::uint64_t seed = 1;
  MovingBoxOptions box;
  cspace::FastronCheckerOptions fk = cspace::FastronCheckerOptions::defaults(cspace::FastronFeatures::kControlPoints);
  cspace::FastronCheckerOptions rbf = cspace::FastronCheckerOptions::defaults(cspace::FastronFeatures::kJoints);
  std::vector<int> obstacle_counts = {1, 2, 5, 10, 20, 30, 40, 50};  // Fig 7
  int obstacle_trials = 3;                                           // per count
};

// One method's numbers, one entry per evaluation (trial x move).
struct MethodSamples {
  std::string name;
  std::vector<double> accuracy, tpr, tnr, query_us, batch_us, support;
  std::vector<double> update_ms, update_label_ms;  // per update (not the initial training)
  std::vector<double> initial_label_ms, initial_learn_ms;  // per trial
  std::vector<double> converged, steps;                    // per training (1: every margin positive)
};

struct ObstacleCountRow {
  int obstacles = 0;
  double collision_fraction = 0;
  double fcl_us = 0, fk_us = 0, rbf_us = 0, fk_support = 0, rbf_support = 0, fk_accuracy = 0, rbf_accuracy = 0;
};

struct CollisionResults {
  MethodSamples fk, rbf, fcl;
  double collision_fraction = 0;  // of the test configurations, mean
  std::vector<ObstacleCountRow> by_obstacles;
};

CollisionResults runCollisionExperiment(const cspace::Scenario& scenario, const CollisionExperimentOptions& options,
                                        std::ostream& log);
void printCollisionTables(const CollisionResults& results, std::ostream& out);
// JSON object text (no trailing newline).
std::string collisionJson(const CollisionResults& results);

}  // namespace svmp::experiments::fastron
