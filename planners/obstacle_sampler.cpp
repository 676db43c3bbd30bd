#include "planners/obstacle_sampler.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <random>
#include <sstream>

#include "cspace/parallel_for.hpp"
#include "planners/nearest_neighbors.hpp"

namespace svmp::planners {

using cspace::ConfigurationSpace;
using cspace::Obstacle;
using cspace::Rng;
using cspace::ValidityChecker;

namespace {

// Polled every this many expansions: often enough for a millisecond limit, rare enough to cost nothing.
constexpr long kStopPollInterval = 64;

bool stopRequested(const ObstacleSamplerOptions& options, long iteration) {
  return options.stop && iteration % kStopPollInterval == 0 && options.stop();
}

// A tree node's state: interior, boundary sample, or bisected once towards no free space.
constexpr char kInterior = 0, kBoundary = 1, kFacesNoFree = 2;

struct Tree {
  std::vector<Eigen::VectorXd> nodes;
  std::vector<char> boundary;  // kInterior, kBoundary or kFacesNoFree
  std::string warning;
  bool stopped = false;
  bool out_of_reach = false;  // then no warning of its own: sampleObstacles names them all in one
  bool no_root = false;       // findRoots found none: named with the others in one warning
};

// Nearest node by a linear scan: trees hold a few hundred nodes, so a scan over contiguous scaled
// coordinates beats maintaining a dynamic k-d tree. With the dimension fixed at compile time the
// compiler unrolls each column's distance: Fig 4.10's sampling 0.91x, panda_shelf's 0.95x
// (docs/benchmarks.md); the same nearest nodes.
template <int D>
int nearestNodeOf(const Eigen::MatrixXd& scaled, int count, const Eigen::VectorXd& x) {
  const Eigen::Map<const Eigen::Matrix<double, D, Eigen::Dynamic>> nodes(scaled.data(), scaled.rows(), scaled.cols());
  const Eigen::Matrix<double, D, 1> target = x;
  int best = 0;
  double best_d = std::numeric_limits<double>::infinity();
  for (int i = 0; i < count; ++i) {
    const double d = (nodes.col(i) - target).squaredNorm();
    if (d < best_d) {
      best_d = d;
      best = i;
    }
  }
  return best;
}

int nearestNode(const Eigen::MatrixXd& scaled, int count, const Eigen::VectorXd& x) {
  return withFixedDimension(static_cast<int>(x.size()),
                            [&](auto d) { return nearestNodeOf<decltype(d)::value>(scaled, count, x); });
}

// No configuration touches it (robots::Robot::mayReach): a root search would spend
// max_root_attempts draws finding nothing (an obstacle beyond an arm's reach: 20k checks).
bool outOfReach(const ValidityChecker& checker, const Obstacle& obstacle) {
  return obstacle.id > 0 && !obstacle.root_sample && !checker.robot().mayReach(obstacle.shape.bounds());
}

// A root drawn uniformly in the obstacle's own box (its bounds in its own frame, then placed), for
// robots that can be put at a point (robots::Robot::configurationAt: a point robot), so it is spread
// over the obstacle as a uniform draw in the whole space that hits it would be (a root at the centre
// left the ends of long walls, where the passages are, unsampled: tunnel3d_zigzag_02 19/20). A few
// draws, each checked. A thin rod turned across the world's axes fills a few percent of its
// axis-aligned box: 16 draws there missed 170 of 1,500 turned capsules, each then searched for by
// 20,000 uniform draws and warned of. An obstacle along the axes is drawn in its world box as
// before (the same box; the same draws to the bit).
std::optional<Eigen::VectorXd> rootInBounds(const ValidityChecker& checker, const Obstacle& obstacle,
                                            std::uint64_t seed) {
  constexpr int kDraws = 16;
  const bool turned = !obstacle.shape.pose.linear().isIdentity(0.0);
  const Eigen::Isometry3d place = turned ? obstacle.shape.pose : Eigen::Isometry3d::Identity();
  const Eigen::AlignedBox3d box = obstacle.shape.boundsAt(turned ? Eigen::Isometry3d::Identity() : obstacle.shape.pose);
  Rng rng(seed ^ (0xC3A5C85C97CB3127ULL * static_cast<std::uint64_t>(obstacle.id)));
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int a = 0; a < kDraws; ++a) {
    Eigen::Vector3d p;
    for (int i = 0; i < 3; ++i) p[i] = box.min()[i] + unit(rng) * (box.max()[i] - box.min()[i]);
    std::optional<Eigen::VectorXd> q = checker.robot().configurationAt(place * p);  // none for an arm
    if (q && checker.hits(*q, obstacle.id)) return q;
  }
  return std::nullopt;
}

// Roots for the targets without a scenario sample: rootInBounds where the robot allows it (forest_200:
// 2.4-5.6 of the 5.8 ms of sampling were the search below), the others from one shared stream of
// uniform draws: check()
// names the (lowest) obstacle a draw hits, so one draw serves whichever target it lands in, where a
// search per target spends about 1/p draws on each (forest_200: 200 boxes of 0.09% of the space
// each, about 220k checks). The search goes on while it keeps finding: it stops when every target
// has a root or after 1000 + 2 x (draws up to the last new root) draws. Then the motions known to be
// blocked (options.blocked_motions) are walked, then one last stream serves the targets still
// without a root (below). `stopped` is set when options.stop ended the search.
std::vector<std::optional<Eigen::VectorXd>> findRoots(const ValidityChecker& checker, const ConfigurationSpace& space,
                                                      const std::vector<const Obstacle*>& targets,
                                                      const ObstacleSamplerOptions& options, std::uint64_t seed,
                                                      bool& stopped) {
  std::vector<std::optional<Eigen::VectorXd>> roots(targets.size());
  std::map<int, size_t> wanted;  // obstacle id -> target index
  for (size_t t = 0; t < targets.size(); ++t) {
    const Obstacle& target = *targets[t];
    if (target.root_sample || outOfReach(checker, target)) continue;
    if (target.id > 0) roots[t] = rootInBounds(checker, target, seed);
    if (!roots[t]) wanted[target.id] = t;
  }
  Eigen::VectorXd q(space.dim());
  const auto found = [&](int hit) {
    const auto it = wanted.find(hit);
    if (it == wanted.end()) return false;
    roots[it->second] = q;
    wanted.erase(it);
    return true;
  };
  if (wanted.size() >= 2) {  // else nothing to share
    Rng rng(seed ^ 0x0B57AC1E5EEDULL);
    long last_found = 0;
    for (long a = 1; !wanted.empty() && a <= options.max_root_attempts && a <= 1000 + 2 * last_found; ++a) {
      if (stopRequested(options, a)) {
        stopped = true;
        break;
      }
      space.sampleUniform(rng, q);
      if (found(options.include_virtual ? checker.checkIncludingVirtual(q) : checker.check(q))) last_found = a;
    }
  }
  // Then along the motions known to be blocked, a step apart (an obstacle thinner than the step is
  // left to the last search, as its tree would pass over it).
  for (const auto& [from, to] : options.blocked_motions) {
    const double steps = std::ceil(space.distance(from, to) / options.step);
    const int n = static_cast<int>(std::clamp(steps, 1.0, static_cast<double>(options.max_root_attempts)));
    for (int i = 0; i <= n && !wanted.empty() && !stopped; ++i) {
      if (stopRequested(options, i)) {
        stopped = true;
        break;
      }
      space.interpolate(from, to, static_cast<double>(i) / n, q);
      found(options.include_virtual ? checker.checkIncludingVirtual(q) : checker.check(q));
    }
  }
  // Last, the targets still without a root (inside a lower-id obstacle, which check() names instead,
  // or rare) share one stream of max_root_attempts draws, each draw asked which obstacles it hits
  // (ValidityChecker::allHits, one check). A search of its own for each had cost max_root_attempts
  // checks apiece (200 discs within an arm's reach but beyond its joint limits: 3.97M checks, 867 ms).
  Rng rng(seed ^ 0x1A57C4A5EULL);
  for (long a = 1; !wanted.empty() && !stopped && a <= options.max_root_attempts; ++a) {
    if (stopRequested(options, a)) {
      stopped = true;
      break;
    }
    space.sampleUniform(rng, q);
    for (const int id : checker.allHits(q, options.include_virtual)) {
      const auto it = wanted.find(id);
      if (it == wanted.end()) continue;
      roots[it->second] = q;
      wanted.erase(it);
    }
  }
  return roots;
}

Tree growTree(const ValidityChecker& checker, const ConfigurationSpace& space, const Obstacle& obstacle,
              const ObstacleSamplerOptions& options, std::uint64_t seed, const std::optional<Eigen::VectorXd>& found_root) {
  Tree tree;
  Rng rng(seed ^ (0x9E3779B97F4A7C15ULL * static_cast<std::uint64_t>(obstacle.id + 1000)));
  Eigen::VectorXd root;
  if (found_root) {
    root = *found_root;
  } else if (obstacle.root_sample) {
    root = *obstacle.root_sample;
    if (!checker.hits(root, obstacle.id)) {
      tree.warning = "obstacle '" + obstacle.name + "': the scenario's sample does not hit it";
      return tree;
    }
  } else {
    tree.out_of_reach = outOfReach(checker, obstacle);
    tree.no_root = !tree.out_of_reach;
    return tree;
  }
  const int n = options.samples_per_tree;
  const Eigen::VectorXd& scale = space.metricScale();
  Eigen::MatrixXd scaled(space.dim(), n);
  tree.nodes.push_back(root);
  tree.boundary.push_back(kInterior);
  scaled.col(0) = root.cwiseProduct(scale);
  Eigen::VectorXd q_rand(space.dim());
  const long max_iterations = static_cast<long>(options.max_iterations_factor) * n;
  long iteration = 0, idle = 0;
  const auto limit = [&](int factor) { return factor * std::max<long>(20, std::ssize(tree.nodes)); };
  const auto thin = [&] { return options.max_expansions_per_node > 0 && iteration > limit(options.max_expansions_per_node); };
  while (static_cast<int>(tree.nodes.size()) < n && iteration++ < max_iterations &&
         idle++ < limit(options.max_idle_factor) && !thin()) {
    if (stopRequested(options, iteration)) {
      tree.stopped = true;
      return tree;
    }
    space.sampleUniform(rng, q_rand);
    const int e = nearestNode(scaled, static_cast<int>(tree.nodes.size()), q_rand.cwiseProduct(scale));
    const Eigen::VectorXd q_new = space.steer(tree.nodes[e], q_rand, options.step);
    if (checker.hits(q_new, obstacle.id)) {
      scaled.col(static_cast<Eigen::Index>(tree.nodes.size())) = q_new.cwiseProduct(scale);
      tree.nodes.push_back(q_new);
      tree.boundary.push_back(kInterior);
      idle = 0;
    } else if (tree.boundary[e] != kBoundary) {
      // q_expansion is a boundary sample when the surface it steps out of faces free space: q_new is
      // free, or the first point beyond the surface is (a gap narrower than the step). Stepping into
      // another obstacle across no free space (their overlap) marks nothing, and the node is bisected
      // that way once (kFacesNoFree) until a q_new of its is free. Without refinement there is no
      // point beyond the surface to ask, and every miss marks the node, as before this rule.
      const bool free_new = !options.refine_boundary || checker.isValid(q_new);
      if (!free_new && tree.boundary[e] == kFacesNoFree) continue;
      Eigen::VectorXd inside = tree.nodes[e], outside = q_new, mid(space.dim());
      if (options.refine_boundary) {
        // Bisection keeps `inside` hitting the obstacle and `outside` missing it.
        const double tolerance = options.refine_tolerance > 0 ? options.refine_tolerance : options.step / 256;
        while (space.distance(inside, outside) > tolerance) {
          mid = 0.5 * (inside + outside);
          (checker.hits(mid, obstacle.id) ? inside : outside) = mid;
        }
      }
      if (!free_new && !checker.isValid(outside)) {
        tree.boundary[e] = kFacesNoFree;
        continue;
      }
      tree.boundary[e] = kBoundary;
      idle = 0;
      if (options.refine_boundary && static_cast<int>(tree.nodes.size()) < n) {
        scaled.col(static_cast<Eigen::Index>(tree.nodes.size())) = inside.cwiseProduct(scale);
        tree.nodes.push_back(inside);
        tree.boundary.push_back(kBoundary);
      }
    }
  }
  if (static_cast<int>(tree.nodes.size()) < n) {
    std::ostringstream w;
    w << "obstacle '" << obstacle.name << "': tree stopped at " << tree.nodes.size() << " of " << n
      << " samples after " << iteration << " expansions ("
      << (iteration > max_iterations ? "the limit"
          : thin() ? "a thin region: under one node per " + std::to_string(options.max_expansions_per_node) + " expansions"
                   : "the last " + std::to_string(idle - 1) + " added nothing")
      << ")";
    tree.warning = w.str();
  }
  return tree;
}

}  // namespace

std::string ObstacleSamplerOptions::validate() const {
  std::ostringstream err;
  if (!(step > 0) || !std::isfinite(step)) err << "step must be positive, got " << step;
  else if (samples_per_tree < 1) err << "samples_per_tree must be >= 1, got " << samples_per_tree;
  else if (max_root_attempts < 1) err << "max_root_attempts must be >= 1";
  else if (max_expansions_per_node < 0) err << "max_expansions_per_node must be >= 0, got " << max_expansions_per_node;
  return err.str();
}

int ObstacleSamples::numBoundary() const {
  int n = 0;
  for (char b : boundary) n += b;
  return n;
}

ObstacleSamples sampleObstacles(const ValidityChecker& checker, const ConfigurationSpace& space,
                                const ObstacleSamplerOptions& options, std::uint64_t seed,
                                int threads) {
  const std::string err = options.validate();
  if (!err.empty()) throw std::invalid_argument("obstacle sampler: " + err);
  std::vector<const Obstacle*> targets;
  for (const auto& o : checker.environment().obstacles())
    if ((!o.is_virtual || options.include_virtual) && !(o.id <= std::ssize(options.skip) && options.skip[o.id - 1]))
      targets.push_back(&o);
  Obstacle self_collision;
  self_collision.id = cspace::kSelfCollisionHit;
  self_collision.name = "self-collision";
  if (options.include_self_collision && checker.checksSelfCollision())
    targets.push_back(&self_collision);
  bool roots_stopped = false;
  const std::vector<std::optional<Eigen::VectorXd>> roots =
      findRoots(checker, space, targets, options, seed, roots_stopped);
  std::vector<Tree> trees(targets.size());
  cspace::parallelFor(static_cast<int>(targets.size()), threads, 1, [&](int t) {
    trees[t] = growTree(checker, space, *targets[t], options, seed, roots[t]);
  });

  ObstacleSamples samples;
  int total = 0;
  for (const auto& tree : trees) total += static_cast<int>(tree.nodes.size());
  samples.points.resize(space.dim(), total);
  int column = 0;
  samples.stopped = roots_stopped;
  // One warning for the obstacles out of reach (crs3_far_near: 300 lines for 300 far boxes), and one
  // for those no draw hit, each naming the first ten.
  std::vector<std::string> far, missed;
  bool self_missed = false;
  for (size_t t = 0; t < trees.size(); ++t) {
    if (trees[t].out_of_reach) far.push_back("'" + targets[t]->name + "'");
    if (trees[t].no_root && !roots_stopped) {
      if (targets[t]->id == cspace::kSelfCollisionHit) self_missed = true;
      else missed.push_back("'" + targets[t]->name + "'");
    }
  }
  const auto warnOf = [&](const std::vector<std::string>& names, const std::string& one, const std::string& many) {
    if (names.empty()) return;
    constexpr size_t kNamed = 10;
    std::string listed = names.front();
    for (size_t i = 1; i < std::min(names.size(), kNamed); ++i) listed += ", " + names[i];
    if (names.size() > kNamed) listed += " and " + std::to_string(names.size() - kNamed) + " more";
    const std::string warning = names.size() == 1
                                    ? "obstacle " + listed + ": " + one
                                    : std::to_string(names.size()) + " obstacles " + many + ": " + listed;
    samples.warnings.push_back(warning);
    samples.unsampled.push_back(warning);
  };
  warnOf(far, "beyond the robot's reach, not sampled", "beyond the robot's reach, not sampled");
  const std::string draws = std::to_string(options.max_root_attempts) + " uniform samples";
  warnOf(missed,
         "no configuration hitting it in " + draws +
             " (beyond the joint limits, or a small target: give `sample:`, a configuration that hits it)",
         "hit by no configuration in " + draws +
             " (beyond the joint limits, or small targets: give each `sample:`, a configuration that hits it)");
  if (self_missed) {
    const std::string warning =
        "the self-collision region: no configuration in " + draws + " collides with the robot itself, not sampled";
    samples.warnings.push_back(warning);
    samples.unsampled.push_back(warning);
  }
  for (size_t t = 0; t < trees.size(); ++t) {
    samples.tree_sizes.push_back(static_cast<int>(trees[t].nodes.size()));
    if (!trees[t].warning.empty()) samples.warnings.push_back(trees[t].warning);
    if (!trees[t].warning.empty() && trees[t].nodes.empty()) samples.unsampled.push_back(trees[t].warning);
    samples.stopped |= trees[t].stopped;
    for (size_t i = 0; i < trees[t].nodes.size(); ++i) {
      samples.points.col(column++) = trees[t].nodes[i];
      samples.labels.push_back(targets[t]->id);
      samples.boundary.push_back(trees[t].boundary[i] == kBoundary);
    }
  }
  return samples;
}

void addBoundsSamples(const ConfigurationSpace& space, int count, std::uint64_t seed, ObstacleSamples& samples) {
  const int dim = space.dim();
  const Eigen::VectorXd extent = (space.upper() - space.lower()).cwiseProduct(space.metricScale());
  // A face normal to axis j measures the product of the other extents: proportional to 1 / extent_j.
  std::vector<double> face_weights(dim);
  for (int j = 0; j < dim; ++j) face_weights[j] = extent[j] > 0 ? 1.0 / extent[j] : 0.0;
  std::discrete_distribution<int> axis_of(face_weights.begin(), face_weights.end());
  std::bernoulli_distribution upper_side(0.5);
  cspace::Rng rng(seed ^ 0xB0B0B0B0ULL);
  const Eigen::Index first = samples.points.cols();
  samples.points.conservativeResize(dim, first + count);
  for (int i = 0; i < count; ++i) {
    Eigen::VectorXd q = space.sampleUniform(rng);
    const int axis = axis_of(rng);
    q[axis] = upper_side(rng) ? space.upper()[axis] : space.lower()[axis];
    samples.points.col(first + i) = q;
    samples.labels.push_back(cspace::kJointLimitHit);
    samples.boundary.push_back(1);
  }
}

}  // namespace svmp::planners
