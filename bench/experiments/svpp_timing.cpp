// svpp-timing: the timing breakdown Miura reports for SVPP (IROS 2006, sec. III-C and IV-C), which
// svmp-plan's per-run table cannot show: per problem, the patterns tried and the mean time of one SVM
// (all patterns, and the patterns with a path: their surface following reached the goal and every
// segment passed the motion validator, not through an obstacle), the path generation time
// of those patterns, and the total planning time (Planner::solve with the certifier, as svmp-plan runs
// it). Planner parameters come from each scenario's `planners.svpp` plus --set KEY=VALUE.
// Usage: svpp-timing [--runs N] [--trials] [--set KEY=VALUE ...] FILE.yaml ...   (exit 2 on bad input;
// --trials lists every pattern's outcome on stderr)
#include <cmath>
#include <cstdio>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench/experiments/driver_options.hpp"
#include "bench/experiments/scenario_check.hpp"
#include "cspace/certified_motion_validator.hpp"
#include "cspace/collision_checker.hpp"
#include "cspace/motion_validator.hpp"
#include "cspace/scenario/scenario.hpp"
#include "planners/svpp_planner.hpp"

namespace {

struct MeanStd {
  std::vector<double> values;
  void add(double v) { values.push_back(v); }
  std::string text() const {
    if (values.empty()) return "-";
    double mean = 0, var = 0;
    for (double v : values) mean += v;
    mean /= values.size();
    for (double v : values) var += (v - mean) * (v - mean);
    const double sd = values.size() > 1 ? std::sqrt(var / (values.size() - 1)) : 0;
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.2f ± %.2f", mean, sd);
    return buffer;
  }
};

}  // namespace

constexpr const char* kUsage =
    "usage: svpp-timing [--runs N] [--trials] [--set [svpp.]KEY=VALUE ...] FILE.yaml ...\n";

int main(int argc, char** argv) {
  using namespace svmp;
  int runs = 1;
  bool list_trials = false;
  std::vector<std::pair<std::string, std::string>> overrides;
  std::vector<std::string> files;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--runs") {
      try {
        runs = static_cast<int>(experiments::parseLong("--runs", i + 1 < argc ? argv[++i] : "", 1, 100000));
      } catch (const std::invalid_argument& e) {
        std::cerr << "svpp-timing: " << e.what() << "\n";
        return 2;
      }
    } else if (arg == "--trials")
      list_trials = true;
    else if (arg == "--set" && i + 1 < argc) {
      const std::string kv = argv[++i];
      const size_t eq = kv.find('=');
      if (eq == std::string::npos) {
        std::cerr << "svpp-timing: --set expects KEY=VALUE, got '" << kv << "'\n";
        return 2;
      }
      // svpp.KEY as svmp-plan spells it, or KEY alone: both name svpp's key.
      const std::string key = kv.rfind("svpp.", 0) == 0 ? kv.substr(5, eq - 5) : kv.substr(0, eq);
      for (const auto& [given, was] : overrides)
        if (given == key) {  // as svmp-plan: the last value would silently win
          std::cerr << "svpp-timing: --set " << kv << ": " << key << " is already set to '" << was << "'\n";
          return 2;
        }
      overrides.emplace_back(key, kv.substr(eq + 1));
    } else if (arg == "--help" || arg == "-h") {
      std::cout << kUsage;
      return 0;
    } else if (arg.rfind("--", 0) == 0) {
      std::cerr << "svpp-timing: unknown flag '" << arg << "'\n" << kUsage;
      return 2;
    } else {
      files.push_back(arg);
    }
  }
  if (files.empty()) {
    std::cerr << kUsage;
    return 2;
  }
  MeanStd all_svm, found_svm, found_path, total, patterns;
  std::cout << "| problem | merged obstacles | samples | patterns | solved | SVM per pattern (ms) "
               "| SVM, path found (ms) "
               "| path generation, path found (ms) | total (ms) |\n| --- | --- | --- | --- | --- | "
               "--- | --- | --- | --- |\n";
  try {
    for (const std::string& file : files) {
      const cspace::Scenario s = cspace::loadScenario(file);
      experiments::requireValidConfigurations(s);
      const cspace::ConfigurationSpace space = s.makeSpace();
      const cspace::CollisionChecker checker(s.robot, s.environment, s.self_collision);
      const cspace::DiscreteMotionValidator validator(checker, space, s.resolution);
      const cspace::CertifiedMotionValidator certifier(checker, space, s.resolution);
      const planners::PlanningContext context{space, checker, validator, 1, &certifier};
      cspace::ParameterSet params = s.paramsFor("svpp");
      for (const auto& [key, value] : overrides)
        params.set(key, value, "flag --set " + key + "=" + value);
      const planners::SvppOptions options = planners::SvppOptions::fromParameters(params);
      params.requireAllUsed();
      planners::SvppPlanner planner(context, options);
      MeanStd p_all, p_found_svm, p_found_path, p_total;
      int solved = 0, samples = 0, tried = 0;
      for (int r = 0; r < runs; ++r) {
        const auto t0 = planners::Clock::now();
        const planners::PlanResult result = planner.solve(s.queries.front(), 1 + r);
        if (result.status == planners::PlanStatus::kInvalidInput)  // another robot: no timing to pool
          throw std::invalid_argument(file + ": " + result.message);
        p_total.add(planners::msSince(t0));
        total.add(p_total.values.back());
        solved += result.solved();
        const auto& trials = planner.trace().trials;
        tried += static_cast<int>(trials.size());
        patterns.add(static_cast<double>(trials.size()));
        for (const auto& t : trials) {
          if (list_trials)
            std::cerr << s.name << " seed " << 1 + r << ": "
                      << planners::followStatusName(t.follow.status) << ", " << t.follow.path.size()
                      << " points, length " << t.follow.length << (t.valid ? ", valid" : "")
                      << ", SVM " << t.svm_ms << " ms (" << t.model.numSupportVectors()
                      << " SVs), path " << t.path_ms << " ms\n";
          p_all.add(t.svm_ms), all_svm.add(t.svm_ms);
          samples = t.samples.size();
          if (!t.valid) continue;
          p_found_svm.add(t.svm_ms), found_svm.add(t.svm_ms);
          p_found_path.add(t.path_ms), found_path.add(t.path_ms);
        }
      }
      std::cout << "| " << s.name << " | " << planner.obstacles().size() << " | " << samples
                << " | " << static_cast<double>(tried) / runs << " | " << solved << "/" << runs
                << " | " << p_all.text() << " | " << p_found_svm.text() << " | "
                << p_found_path.text() << " | " << p_total.text() << " |\n";
    }
  } catch (const std::exception& e) {
    std::cerr << "svpp-timing: " << e.what() << "\n";
    return 2;
  }
  std::cout << "| **all** | | | " << patterns.text() << " | | " << all_svm.text() << " | "
            << found_svm.text() << " | " << found_path.text() << " | " << total.text() << " |\n";
  return 0;
}
