#pragma once
// When a planner must give up: a wall-clock deadline and, optionally, a caller's condition (OMPL's
// PlannerTerminationCondition is bridged to this in planners/ompl_bridge.cpp). Every planner polls it
// between steps and inside its long loops and returns PlanStatus::kTimeout when it fires.
//
// Thread safety: immutable after construction; operator() may be called from many threads at once when
// the caller's condition may be (the deadline alone always may).
#include <chrono>
#include <cmath>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>

namespace svmp::planners {

class Termination {
 public:
  using Clock = std::chrono::steady_clock;

  // Never fires.
  Termination() = default;
  // Fires `seconds` from now; throws std::invalid_argument unless seconds is positive (inf: never).
  static Termination after(double seconds) {
    if (!(seconds > 0)) throw std::invalid_argument("time limit must be positive, got " + std::to_string(seconds));
    Termination t;
    if (std::isfinite(seconds) && seconds < 1e9)
      t.deadline_ = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
    return t;
  }
  // Fires when `condition` returns true (or at the deadline of `base`).
  static Termination when(std::function<bool()> condition, Termination base = {}) {
    base.condition_ = std::move(condition);
    return base;
  }

  bool operator()() const { return (deadline_ && Clock::now() >= *deadline_) || (condition_ && condition_()); }
  // True when a wall-clock deadline bounds it (a run's --time-limit), not only a caller's condition.
  bool hasDeadline() const { return deadline_.has_value(); }
  // As a callable for code outside planners/ (the obstacle sampler's stop hook).
  std::function<bool()> asFunction() const { return [t = *this] { return t(); }; }

 private:
  std::optional<Clock::time_point> deadline_;
  std::function<bool()> condition_;
};

}  // namespace svmp::planners
