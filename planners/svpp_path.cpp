#include "planners/svpp_path.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

#include "svm/truncated_evaluator.hpp"

namespace svmp::planners {
namespace {

// V is evaluated thousands of times per following (arc searches, bisections, plane fits): by the
// evaluator's exact sum, the full sum at a fraction of the model's scalar loop (svpp_3d20_01: 61% of
// svpp's time was that loop).
using Evaluator = svm::TruncatedRbfEvaluator;

constexpr int kArcSamples = 25;  // points on the 2-D search arc (5 deg apart over 120 deg)
constexpr int kBisections = 30;
constexpr int kCirclePoints = 8;  // plane points of the 3-D fit
constexpr int kNewtonSteps = 6;

double decision(const Evaluator& v, const Eigen::VectorXd& p) { return v.exactDecision(p.data()); }

bool inside(const Eigen::VectorXd& p, const SurfaceFollowing& o) {
  return (p.array() >= o.lower.array()).all() && (p.array() <= o.upper.array()).all();
}

// Appends p; false (with the status set) when the search must end there. The length so far plus the
// straight distance left is a lower bound on the final length, so a path is cut as soon as it
// exceeds max_length.
bool advance(FollowResult& r, const Eigen::VectorXd& p, const Eigen::VectorXd& goal,
             const SurfaceFollowing& o) {
  r.length += (p - r.path.back()).norm();
  r.path.push_back(p);
  if (!inside(p, o))
    r.status = FollowStatus::kLeftSpace;
  else if (r.length + (goal - p).norm() > o.max_length)
    r.status = FollowStatus::kTooLong;
  else
    return true;
  return false;
}

// Ends the path at the goal when it is within one step; a last point within a quarter step of the
// goal is replaced by it (a sliver segment would make a spurious corner).
bool closeToGoal(FollowResult& r, const Eigen::VectorXd& goal, const SurfaceFollowing& o) {
  if ((goal - r.path.back()).norm() > o.step) return false;
  if (r.path.size() > 1 && (goal - r.path.back()).norm() < 0.25 * o.step) {
    r.length -= (r.path.back() - r.path[r.path.size() - 2]).norm();
    r.path.pop_back();
  }
  r.length += (goal - r.path.back()).norm();
  r.path.push_back(goal);
  r.status = r.length > o.max_length ? FollowStatus::kTooLong : FollowStatus::kReached;
  return true;
}

// An orthonormal pair spanning the plane with unit normal n.
std::pair<Eigen::Vector3d, Eigen::Vector3d> planeBasis(const Eigen::Vector3d& n) {
  const Eigen::Vector3d trial =
      std::abs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  const Eigen::Vector3d e1 = (trial - trial.dot(n) * n).normalized();
  return {e1, n.cross(e1)};
}

// Sum over points on the circle of radius r in the plane (p, n) of their distance to V = 0, to
// first order |V(x)| / |grad V(p)|; the gradient norm at p is one factor for all planes, so it is
// left out.
double fitCost(const Evaluator& v, const Eigen::Vector3d& p, const Eigen::Vector3d& n, double r) {
  const auto [e1, e2] = planeBasis(n);
  double cost = 0;
  for (int k = 0; k < kCirclePoints; ++k) {
    const double a = 2 * std::numbers::pi * k / kCirclePoints;
    const Eigen::Vector3d x = p + r * (std::cos(a) * e1 + std::sin(a) * e2);
    cost += std::abs(v.exactDecision(x.data()));
  }
  return cost;
}

// The local plane fit of Fig. 5 at p: the unit normal of the best plane.
Eigen::Vector3d fitSurfacePlane(const Evaluator& v, const Eigen::Vector3d& p, double radius) {
  Eigen::Vector3d grad;
  v.exactDecisionAndGradient(p.data(), grad.data());
  Eigen::Vector3d normal =
      grad.norm() > 1e-12 ? Eigen::Vector3d(grad.normalized()) : Eigen::Vector3d::UnitZ();
  // Pitch and roll about the current normal on 3 x 3 grids of shrinking span (+-20, +-6.7, +-2.2
  // deg).
  double span = std::numbers::pi / 9;
  double best = fitCost(v, p, normal, radius);
  for (int level = 0; level < 3; ++level, span /= 3) {
    const auto [e1, e2] = planeBasis(normal);
    Eigen::Vector3d best_normal = normal;
    for (int i = -1; i <= 1; ++i)
      for (int j = -1; j <= 1; ++j) {
        if (i == 0 && j == 0) continue;
        const Eigen::Vector3d n =
            (normal + std::tan(span * i) * e1 + std::tan(span * j) * e2).normalized();
        const double cost = fitCost(v, p, n, radius);
        if (cost < best) best = cost, best_normal = n;
      }
    normal = best_normal;
  }
  return normal;
}

}  // namespace

const char* followStatusName(FollowStatus status) {
  switch (status) {
    case FollowStatus::kReached:
      return "reached the goal";
    case FollowStatus::kNoSafePoint:
      return "no next point with |V| < 1";
    case FollowStatus::kStepLimit:
      return "step limit";
    case FollowStatus::kLeftSpace:
      return "left the space";
    case FollowStatus::kTooLong:
      return "longer than a path already found";
    case FollowStatus::kStopped:
      return "stopped by the time limit";
  }
  return "?";
}

FollowResult followSurface2d(const svm::BinaryModel& model, const Eigen::VectorXd& start,
                             const Eigen::VectorXd& goal, const Eigen::VectorXd& heading,
                             const SurfaceFollowing& o) {
  const Evaluator full(model);
  FollowResult r;
  r.path = {start};
  double direction = std::atan2(heading.y(), heading.x());
  const auto arcPoint = [&](double angle) {
    const Eigen::VectorXd& p = r.path.back();
    return Eigen::Vector2d(p.x() + o.step * std::cos(angle), p.y() + o.step * std::sin(angle));
  };
  for (int step = 0; step < o.max_steps; ++step) {
    if (closeToGoal(r, goal, o)) return r;
    if (o.stop && o.stop()) {
      r.status = FollowStatus::kStopped;
      return r;
    }
    double angles[kArcSamples], values[kArcSamples];
    for (int k = 0; k < kArcSamples; ++k) {
      angles[k] = direction - o.search_angle / 2 + o.search_angle * k / (kArcSamples - 1);
      values[k] = decision(full, arcPoint(angles[k]));
    }
    // The zero crossing nearest the heading, else the arc point of smallest |V|.
    double best_angle = 0, best_offset = 1e300;
    bool found = false;
    for (int k = 0; k + 1 < kArcSamples; ++k) {
      if ((values[k] > 0) == (values[k + 1] > 0)) continue;
      double lo = angles[k], hi = angles[k + 1], v_lo = values[k];
      for (int b = 0; b < kBisections; ++b) {
        const double mid = 0.5 * (lo + hi), v = decision(full, arcPoint(mid));
        if ((v > 0) == (v_lo > 0))
          lo = mid, v_lo = v;
        else
          hi = mid;
      }
      const double angle = 0.5 * (lo + hi);
      if (std::abs(angle - direction) < best_offset)
        best_offset = std::abs(angle - direction), best_angle = angle;
      found = true;
    }
    if (!found) {
      int k_min = 0;
      for (int k = 1; k < kArcSamples; ++k)
        if (std::abs(values[k]) < std::abs(values[k_min])) k_min = k;
      if (!(std::abs(values[k_min]) < 1.0)) {
        r.status = FollowStatus::kNoSafePoint;
        return r;
      }
      best_angle = angles[k_min];
    }
    direction = best_angle;
    if (!advance(r, arcPoint(best_angle), goal, o)) return r;
  }
  r.status = FollowStatus::kStepLimit;
  return r;
}

FollowResult followSurface3d(const svm::BinaryModel& model, const Eigen::VectorXd& start,
                             const Eigen::VectorXd& goal,
                             const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& target,
                             const SurfaceFollowing& o) {
  const Evaluator full(model);
  FollowResult r;
  r.path = {start};
  Eigen::Vector3d grad;
  for (int step = 0; step < o.max_steps; ++step) {
    if (closeToGoal(r, goal, o)) return r;
    if (o.stop && o.stop()) {
      r.status = FollowStatus::kStopped;
      return r;
    }
    const Eigen::Vector3d p = r.path.back();
    const Eigen::Vector3d normal = fitSurfacePlane(full, p, o.step);
    Eigen::Vector3d direction = target(p) - p;
    direction -= direction.dot(normal) * normal;
    if (!(direction.norm() > 1e-12)) {  // the plane faces the target: no way along the surface
      r.status = FollowStatus::kNoSafePoint;
      return r;
    }
    Eigen::Vector3d next = p + o.step * direction.normalized();
    double v = 0;
    for (int k = 0; k < kNewtonSteps; ++k) {
      v = full.exactDecisionAndGradient(next.data(), grad.data());
      const double g2 = grad.squaredNorm();
      if (std::abs(v) < 1e-6 || g2 < 1e-24) break;
      Eigen::Vector3d correction = -(v / g2) * grad;
      if (correction.norm() > 0.5 * o.step) correction *= 0.5 * o.step / correction.norm();
      next += correction;
    }
    v = full.exactDecision(next.data());
    if (!(std::abs(v) < 1.0)) {
      r.status = FollowStatus::kNoSafePoint;
      return r;
    }
    if (!advance(r, next, goal, o)) return r;
  }
  r.status = FollowStatus::kStepLimit;
  return r;
}

}  // namespace svmp::planners
