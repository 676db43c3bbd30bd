// SVMP's milestones (thesis ch. 3.3, FindBoundaryMilestones): boundary samples descend the risk of
// their class to its decision boundary; the ends that are new (NearDuplicateFilter) and free join the
// roadmap. An end that collides lies where the boundary, smooth at the scale sigma, misses a passage
// narrower than sigma: it is centred along the boundary's normal (centreAlongNormal), at once or
// deferred until a query needs it (docs/dev-log.md, "Centring when a query needs it").
#include <atomic>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

#include "cspace/parallel_for.hpp"
#include "planners/svmp_planner.hpp"

namespace svmp::planners {

int SvmpPlanner::addMilestones(const std::vector<Eigen::VectorXd>& starts, const std::vector<int>& classes,
                               const Termination& stop, bool keep_free_starts, double duplicate_radius,
                               bool defer_centring) {
  int n = static_cast<int>(starts.size());
  std::vector<Eigen::VectorXd> ends(n);
  std::vector<int> end_class(n);
  const DescentOptions descent = options_.descent();
  std::atomic<bool> stopped{false};
  cspace::parallelFor(n, context_.threads, 8, [&](int i) {
    if (stopped.load(std::memory_order_relaxed) || (stop() && (stopped = true))) return;
    const int k = classes[i] >= 0 ? classes[i] : nearestBoundary(starts[i]);
    ends[i] = risk_->descend(k, starts[i], context_.space, descent).q;
    end_class[i] = k;
  });
  if (stopped) return 0;
  // With keep_free_starts the starts themselves are candidates too (raw: no centring).
  std::vector<char> raw(n, 0);
  if (keep_free_starts) {
    ends.insert(ends.end(), starts.begin(), starts.end());
    const std::vector<int> descended_class = end_class;  // insert must not read its own vector
    end_class.insert(end_class.end(), descended_class.begin(), descended_class.end());
    raw.resize(2 * n, 1);
    n *= 2;
  }
  // Near-duplicates are dropped before any collision check, in a fixed order (deterministic).
  if (duplicate_radius < 0) duplicate_radius = options_.duplicate_radius;
  NearDuplicateFilter kept(context_.space, duplicate_radius, roadmap_.numNodes() + n);
  for (const auto& q : roadmap_.nodes()) kept.add(q);
  std::vector<int> fresh;
  for (int i = 0; i < n; ++i)
    if (kept.addUnlessNear(ends[i])) fresh.push_back(i);
  std::vector<char> valid(fresh.size());
  cspace::parallelFor(static_cast<int>(fresh.size()), context_.threads, 8, [&](int f) {
    valid[f] = context_.checker.isValid(ends[fresh[f]]);
    if (valid[f] || raw[fresh[f]] || defer_centring) return;
    std::optional<Eigen::VectorXd> centre;
    if (options_.centre_in_passage) centre = centreAlongNormal(end_class[fresh[f]], ends[fresh[f]]);
    if (centre) {
      ends[fresh[f]] = *centre;
      valid[f] = 1;
    }
  });
  int added = 0;
  for (size_t f = 0; f < fresh.size(); ++f) {
    if (valid[f])
      roadmap_.addNode(ends[fresh[f]]), ++added;
    else if (defer_centring && !raw[fresh[f]])
      uncentred_.emplace_back(ends[fresh[f]], end_class[fresh[f]]);
  }
  return added;
}

int SvmpPlanner::centreDeferred() {
  const int n = static_cast<int>(uncentred_.size());
  std::vector<std::optional<Eigen::VectorXd>> centres(n);
  cspace::parallelFor(n, context_.threads, 8,
                      [&](int i) { centres[i] = centreAlongNormal(uncentred_[i].second, uncentred_[i].first); });
  uncentred_.clear();
  int added = 0;
  for (const auto& c : centres)
    if (c) roadmap_.addNode(*c), ++added;
  if (added > 0) nn_->extend(roadmap_.nodes());
  return added;
}

bool SvmpPlanner::findBoundaryMilestones(PhaseTimes& times, const Termination& stop) {
  if (!risk_) throw std::logic_error("svmp: findBoundaryMilestones before trainMultiSvm");
  const auto t0 = Clock::now();
  std::vector<Eigen::VectorXd> starts;
  std::vector<int> classes;
  for (int i = 0; i < samples_.size(); ++i) {
    if (!samples_.boundary[i]) continue;
    starts.push_back(samples_.points.col(i));
    classes.push_back(risk_->classIndex(class_of_label_.at(samples_.labels[i])));
  }
  addMilestones(starts, classes, stop, false, -1,
                options_.lazy && options_.centre_in_passage && options_.defer_centring);
  times.milestones_ms += msSince(t0);
  return !stop();
}

std::optional<Eigen::VectorXd> SvmpPlanner::centreAlongNormal(int k, const Eigen::VectorXd& q) const {
  const Eigen::VectorXd& scale = context_.space.metricScale();
  Eigen::VectorXd grad(q.size());
  risk_->decisionAndGradient(k, q, grad);
  Eigen::VectorXd normal = grad.cwiseQuotient(scale);  // dF/dx in scaled coordinates
  if (!(normal.norm() > 0)) return std::nullopt;
  normal.normalize();
  const Eigen::VectorXd direction = normal.cwiseQuotient(scale);  // unit length in the metric
  auto at = [&](double t) {
    Eigen::VectorXd p = q + t * direction;
    context_.space.clamp(p);
    return p;
  };
  auto free = [&](double t) { return context_.checker.isValid(at(t)); };
  const double first = context_.validator.resolution() / 4, tolerance = first / 8;
  const double sigma = options_.sigma;
  // The last free offset from the free offset t0 going the way of `sign` (steps doubling from
  // `first`, then bisection); empty when all is free within sigma of q.
  auto edge = [&](double t0, double sign) -> std::optional<double> {
    double clear = t0, blocked = t0;
    for (double step = first;; step *= 2) {
      const double probe = t0 + sign * step;
      if (std::abs(probe) > sigma) return std::nullopt;
      if (!free(probe)) {
        blocked = probe;
        break;
      }
      clear = probe;
    }
    while (std::abs(blocked - clear) > tolerance) {
      const double mid = 0.5 * (blocked + clear);
      (free(mid) ? clear : blocked) = mid;
    }
    return clear;
  };
  std::optional<double> entry, exit;
  if (free(0)) {
    entry = edge(0, -1);
    exit = edge(0, 1);
    if (!entry || !exit) return q;  // not in a passage narrower than 2 sigma
  } else {
    // The nearest free offset on either side, by doubling; the passage extends from it both ways.
    double outside = 0;
    for (double t = first; t <= sigma && outside == 0; t *= 2)
      for (double signed_t : {t, -t})
        if (free(signed_t)) {
          outside = signed_t;
          break;
        }
    if (outside == 0) return std::nullopt;
    const double sign = outside > 0 ? 1 : -1;
    entry = edge(outside, -sign);
    exit = edge(outside, sign).value_or(sign * sigma);
    if (!entry) return std::nullopt;
  }
  const Eigen::VectorXd centre = at(0.5 * (*entry + *exit));
  if (!context_.checker.isValid(centre)) return std::nullopt;
  return centre;
}

int SvmpPlanner::nearestBoundary(const Eigen::VectorXd& q) const {
  int k = 0;
  double lowest = std::numeric_limits<double>::infinity();
  for (int c = 0; c < risk_->numClasses(); ++c)
    if (const double r = risk_->risk(c, q); r < lowest) lowest = r, k = c;
  return k;
}

std::optional<Eigen::VectorXd> SvmpPlanner::inPassage(int k, const Eigen::VectorXd& q) const {
  if (options_.centre_in_passage) return centreAlongNormal(k, q);
  if (context_.checker.isValid(q)) return q;
  return std::nullopt;
}

}  // namespace svmp::planners
