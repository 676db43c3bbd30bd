#pragma once
// Certified motion validation (Schwarzer, Saha and Latombe, "Exact collision checking of robot
// paths", WAFR 2002 / IEEE T-RO 2005): a straight segment q(t) = a + t (b - a) is valid when proven
// so, not when sampled. Per link k, as they do: at a configuration q the exact checker gives d_k(q),
// a lower bound on the distance from link k to every real obstacle and, for each non-adjacent pair
// with k as its distal link, to the other link; the link's displacement bound L_k
// (robots/robot.hpp: no point of link k moves farther than L_k t over [0, t] of the segment, also
// relative to the links nearer the base) makes [t0, t1] free when d_k(t0) + d_k(t1) > (t1 - t0) L_k
// for every k: the two free balls cover the interval. A link near the base, which moves little, no
// longer needs the hand's bound. Intervals that are not covered are bisected. A configuration closer
// than `tolerance` to contact, or more than kMaxDistanceQueries queries for one segment, ends the
// proof as not valid (never valid unless proven). The query cap bounds what a grazing segment costs:
// covering length at clearance d takes about L_k / (2 d) queries, so 10,000 reject a segment that
// slides along an obstacle within about a tenth of a millimetre (arm links, L_k ~ 1 m). Over the 73
// bench files, 20 seeds each, one proof needed more (panda_shelf seed 13: 64k queries, 87 ms); the
// next-largest needed 3.3k. FCL's continuous collision (conservative
// advancement) would do the same for single bodies, but not for an articulated chain with
// self-collision pairs, and it costs more per query; see docs/architecture.md. Each call counts one
// local planner call here; each distance query one distance query in the exact checker.
//
// d_k is a separating plane's, not FCL's distance (FCL 0.7's GJK overestimates; see
// cspace/convex_distance.hpp), and capped at L_k (more proves nothing), so distant pairs are skipped
// by their bounding boxes.
//
// Tolerance: 1e-6 x resolution, read as a workspace length (a resolution step moves an arm's points
// by at most about resolution x reach, reach ~1 m here), so a path that grazes an obstacle closer
// than that is rejected; it only has to keep the bisection finite, as any positive value keeps the
// proof sound.
//
// Thread safety: every const method may be called from many threads at once.
#include "cspace/collision_checker.hpp"
#include "cspace/motion_validator.hpp"

namespace svmp::cspace {

class CertifiedMotionValidator final : public MotionValidator {
 public:
  static constexpr std::int64_t kMaxDistanceQueries = 10000;

  // Throws std::invalid_argument when resolution is not positive and finite.
  CertifiedMotionValidator(const CollisionChecker& exact, const ConfigurationSpace& space, double resolution);

  // Proves the segment, end points included (a segment whose end touches an obstacle is not valid).
  bool isValid(const Eigen::Ref<const Eigen::VectorXd>& a,
               const Eigen::Ref<const Eigen::VectorXd>& b) const override;
  bool checkMotion(const Eigen::Ref<const Eigen::VectorXd>& a, const Eigen::Ref<const Eigen::VectorXd>& b,
                   double& last_valid) const override;

  const ValidityChecker& checker() const override { return exact_; }
  const ConfigurationSpace& space() const override { return space_; }
  double resolution() const override { return resolution_; }
  double tolerance() const { return tolerance_; }
  // Closer than this to contact nothing is proven free: a start or goal within it has no provable path.
  static double toleranceFor(double resolution) { return 1e-6 * resolution; }
  std::uint64_t distanceQueries() const override { return distances_.load(std::memory_order_relaxed); }

 private:
  // Proves [0, 1] from a, in order; on failure `proven` is the largest t with [0, t] proven (computed
  // only with need_prefix; without it an end in contact fails at once).
  bool prove(const Eigen::Ref<const Eigen::VectorXd>& a, const Eigen::Ref<const Eigen::VectorXd>& b,
             bool need_prefix, double& proven) const;

  const CollisionChecker& exact_;
  const ConfigurationSpace& space_;
  double resolution_, tolerance_;
  mutable std::atomic<std::uint64_t> distances_{0};
};

}  // namespace svmp::cspace
