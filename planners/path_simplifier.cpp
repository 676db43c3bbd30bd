#include "planners/path_simplifier.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>

namespace svmp::planners {
namespace {

using Path = std::vector<Eigen::VectorXd>;

// Joins random pairs of vertices at most range_ratio of the path apart when the straight segment
// between them is proven free (OMPL reduceVertices).
bool reduceVertices(Path& path, const cspace::MotionValidator& certifier, cspace::Rng& rng,
                    const SimplifyOptions& o, int& proven) {
  bool changed = false;
  const int max_empty = o.max_empty_steps > 0 ? o.max_empty_steps : static_cast<int>(path.size());
  for (int empty = 0; empty < max_empty && path.size() > 2;) {
    const int n = static_cast<int>(path.size());
    const int range = std::max(2, static_cast<int>(std::floor(0.5 + o.range_ratio * n)));
    const int i = std::uniform_int_distribution<int>(0, n - 1)(rng);
    const int j = std::uniform_int_distribution<int>(std::max(0, i - range), std::min(n - 1, i + range))(rng);
    const int lo = std::min(i, j), hi = std::max(i, j);
    ++empty;
    if (hi - lo < 2) continue;
    ++proven;
    if (!certifier.isValid(path[lo], path[hi])) continue;
    path.erase(path.begin() + lo + 1, path.begin() + hi);
    changed = true;
    empty = 0;
  }
  return changed;
}

// Connects two random points on the path (by arc length) when the segment between them is proven free
// and shorter than the stretch it replaces (OMPL shortcutPath).
bool shortcut(Path& path, const cspace::MotionValidator& certifier, const cspace::ConfigurationSpace& space,
              cspace::Rng& rng, const SimplifyOptions& o, int& proven) {
  bool changed = false;
  const int max_empty = o.max_empty_steps > 0 ? o.max_empty_steps : static_cast<int>(path.size());
  for (int empty = 0; empty < max_empty && path.size() > 2;) {
    ++empty;
    std::vector<double> cumulative(path.size(), 0.0);
    for (size_t i = 1; i < path.size(); ++i) cumulative[i] = cumulative[i - 1] + space.distance(path[i - 1], path[i]);
    const double total = cumulative.back();
    if (!(total > 0)) break;
    std::uniform_real_distribution<double> along(0.0, total);
    double s0 = along(rng), s1 = along(rng);
    if (s0 > s1) std::swap(s0, s1);
    // Segment indices: point at arc length s lies on segment [seg, seg + 1].
    auto segment = [&](double s) {
      const size_t k = std::upper_bound(cumulative.begin(), cumulative.end(), s) - cumulative.begin();
      return static_cast<int>(std::clamp<size_t>(k, 1, path.size() - 1)) - 1;
    };
    const int a = segment(s0), b = segment(s1);
    if (a == b) continue;  // on one straight segment already
    auto at = [&](int seg, double s) {
      const double span = cumulative[seg + 1] - cumulative[seg];
      const double t = span > 0 ? (s - cumulative[seg]) / span : 0;
      return Eigen::VectorXd(path[seg] + t * (path[seg + 1] - path[seg]));
    };
    const Eigen::VectorXd pa = at(a, s0), pb = at(b, s1);
    if (!(space.distance(pa, pb) < s1 - s0 - 1e-12)) continue;
    ++proven;
    if (!certifier.isValid(pa, pb)) continue;
    // The new points lie on proven segments; the pieces path[a]-pa and pb-path[b+1] are parts of them.
    Path next(path.begin(), path.begin() + a + 1);
    if (space.distance(next.back(), pa) > 0) next.push_back(pa);
    if (space.distance(pb, path[b + 1]) > 0) next.push_back(pb);
    next.insert(next.end(), path.begin() + b + 1, path.end());
    path = std::move(next);
    changed = true;
    empty = 0;
  }
  return changed;
}

}  // namespace

std::string SimplifyOptions::validate() const {
  if (rounds < 0 || max_empty_steps < 0) return "rounds and max_empty_steps must be >= 0";
  if (!(range_ratio > 0 && range_ratio <= 1)) return "range_ratio must be in (0, 1]";
  return "";
}

SimplifyResult simplifyPath(const std::vector<Eigen::VectorXd>& path, const cspace::MotionValidator& certifier,
                            const cspace::ConfigurationSpace& space, cspace::Rng& rng,
                            const SimplifyOptions& options) {
  if (const std::string err = options.validate(); !err.empty())
    throw std::invalid_argument("path simplifier: " + err);
  SimplifyResult result{path, 0};
  for (int round = 0; round < options.rounds; ++round) {
    const bool reduced = reduceVertices(result.path, certifier, rng, options, result.segments_proven);
    const bool shortened = shortcut(result.path, certifier, space, rng, options, result.segments_proven);
    if (!reduced && !shortened) break;
  }
  return result;
}

double pathLength(const std::vector<Eigen::VectorXd>& path, const cspace::ConfigurationSpace& space) {
  double length = 0;
  for (size_t i = 1; i < path.size(); ++i) length += space.distance(path[i - 1], path[i]);
  return length;
}

double minClearance(const std::vector<Eigen::VectorXd>& path, const cspace::ValidityChecker& checker,
                    const cspace::ConfigurationSpace& space, double step) {
  if (path.empty()) return std::numeric_limits<double>::quiet_NaN();
  double least = checker.clearance(path.front());
  Eigen::VectorXd q(space.dim());
  for (size_t i = 1; i < path.size(); ++i) {
    // In double before converting: the loader bounds segment lengths, this keeps any count finite.
    const double pieces = std::min(std::max(1.0, std::ceil(space.distance(path[i - 1], path[i]) / step)),
                                   static_cast<double>(cspace::kMaxSegmentChecks));
    const auto n = static_cast<std::int64_t>(pieces);
    const double per_piece = checker.robot().displacementBound(path[i - 1], path[i]) / pieces;
    for (std::int64_t k = 1; k <= n;) {
      space.interpolate(path[i - 1], path[i], static_cast<double>(k) / pieces, q);
      const double c = checker.clearance(q);
      least = std::min(least, c);
      // Points k + 1 .. k + skip lie within skip x per_piece of q: at clearance >= c - that >= least.
      // (Comparisons false on NaN, infinite clearances without obstacles: the segment is done.)
      double skip = pieces;
      if (per_piece > 0 && c - least < pieces * per_piece) skip = std::floor((c - least) / per_piece);
      k += 1 + static_cast<std::int64_t>(skip);
    }
  }
  return least;
}

double smoothness(const std::vector<Eigen::VectorXd>& path, const cspace::ConfigurationSpace& space) {
  double s = 0;
  for (size_t i = 2; i < path.size(); ++i) {
    const double a = space.distance(path[i - 2], path[i - 1]);
    const double b = space.distance(path[i - 1], path[i]);
    const double c = space.distance(path[i - 2], path[i]);
    if (!(a > 0 && b > 0)) continue;
    const double cosine = (a * a + b * b - c * c) / (2 * a * b);
    if (cosine > 1 || cosine < -1) continue;
    const double turn = std::numbers::pi - std::acos(cosine);
    const double k = 2 * turn / (a + b);
    s += k * k;
  }
  return s;
}

}  // namespace svmp::planners
