#include "cspace/environment.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "cspace/convex_distance.hpp"

namespace svmp::cspace {

Environment::Environment(std::vector<Obstacle> obstacles) : obstacles_(std::move(obstacles)) {
  for (size_t i = 0; i < obstacles_.size(); ++i) {
    Obstacle& o = obstacles_[i];
    o.id = static_cast<int>(i) + 1;
    if (o.name.empty()) o.name = "obstacle" + std::to_string(o.id);
    const std::string err = o.shape.validate();
    if (!err.empty()) throw std::invalid_argument("obstacle '" + o.name + "': " + err);
    if (!std::isfinite(o.weight) || !(o.weight > 0))
      throw std::invalid_argument("obstacle '" + o.name + "': weight must be positive, got " +
                                  std::to_string(o.weight));
  }
}

const Obstacle& Environment::byId(int id) const {
  if (id < 1 || id > size()) throw std::out_of_range("no obstacle with id " + std::to_string(id));
  return obstacles_[id - 1];
}

int Environment::numReal() const {
  int n = 0;
  for (const auto& o : obstacles_) n += !o.is_virtual;
  return n;
}

namespace {

// Whether `inner` lies inside `outer` (both posed in the world): its support points along the 26
// directions of the cube round the origin, in the world's frame and in either shape's, shrunk by 1e-9
// towards its centre (identical shapes are inside each other despite rounding). Exact when either
// shape is a box (the outer box's face normals, the inner box's corners are among them); a round
// shape inside another round one may poke out by up to about 3% of its size, where the two overlap
// so much that one class for both changes nothing.
bool inside(const robots::Shape& inner, const robots::Shape& outer) {
  const Eigen::Vector3d centre = inner.pose.translation();
  const Eigen::Matrix3d frames[] = {Eigen::Matrix3d::Identity(), inner.pose.linear(), outer.pose.linear()};
  for (const Eigen::Matrix3d& frame : frames)
    for (int x = -1; x <= 1; ++x)
      for (int y = -1; y <= 1; ++y)
        for (int z = -1; z <= 1; ++z) {
          if (x == 0 && y == 0 && z == 0) continue;
          const Eigen::Vector3d p = supportPoint(inner, inner.pose, frame * Eigen::Vector3d(x, y, z));
          if (!outer.contains(p + 1e-9 * (centre - p))) return false;
        }
  return true;
}

}  // namespace

std::vector<int> Environment::nestedGroups() const {
  const int n = size();
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  auto root = [&](int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  std::vector<Eigen::AlignedBox3d> box(n);
  std::vector<int> order;
  for (int i = 0; i < n; ++i)
    if (!obstacles_[i].is_virtual) box[i] = obstacles_[i].shape.bounds(), order.push_back(i);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return box[a].min().x() < box[b].min().x(); });
  for (size_t u = 0; u < order.size(); ++u)
    for (size_t v = u + 1; v < order.size() && box[order[v]].min().x() <= box[order[u]].max().x(); ++v) {
      const int i = order[u], j = order[v];
      if (root(i) == root(j) || !box[i].intersects(box[j])) continue;
      const robots::Shape &a = obstacles_[i].shape, &b = obstacles_[j].shape;
      if (inside(b, a) || inside(a, b))
        parent[std::max(root(i), root(j))] = std::min(root(i), root(j));
    }
  std::vector<int> group(n);
  for (int i = 0; i < n; ++i) group[i] = root(i) + 1;
  return group;
}

std::vector<char> Environment::innerObstacles(const std::vector<int>& groups) const {
  const int n = size();
  if (static_cast<int>(groups.size()) != n) throw std::invalid_argument("innerObstacles: one group per obstacle");
  std::vector<std::vector<int>> members(n + 1);
  for (int i = 0; i < n; ++i) {
    if (groups[i] < 1 || groups[i] > n) throw std::invalid_argument("innerObstacles: a group id outside [1, n]");
    if (!obstacles_[i].is_virtual) members[groups[i]].push_back(i);
  }
  // Inside and exactly so: `inside` is exact where either shape is a box, and a shape given twice is
  // itself; a round shape in a round one may poke out, and that part would go unsampled.
  const auto covered = [&](int i, int k) {
    const robots::Shape &a = obstacles_[i].shape, &b = obstacles_[k].shape;
    const bool same = a.kind == b.kind && a.dims == b.dims && a.pose.matrix() == b.pose.matrix();
    return (same || a.kind == robots::ShapeKind::kBox || b.kind == robots::ShapeKind::kBox) && inside(a, b);
  };
  std::vector<char> inner(n, 0);
  std::vector<double> volume(n);
  for (int i = 0; i < n; ++i) volume[i] = obstacles_[i].shape.bounds().volume();
  for (std::vector<int>& group : members) {
    if (group.size() < 2) continue;
    std::stable_sort(group.begin(), group.end(), [&](int a, int b) { return volume[a] > volume[b]; });
    std::vector<int> kept;
    for (int i : group) {
      // One given a `sample:` is sampled from it (the kept one may have none, and miss its root).
      if (!obstacles_[i].root_sample && std::any_of(kept.begin(), kept.end(), [&](int k) { return covered(i, k); }))
        inner[i] = 1;
      else
        kept.push_back(i);
    }
  }
  return inner;
}

}  // namespace svmp::cspace
