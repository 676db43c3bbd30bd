#include "cspace/collision_checker.hpp"

#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <unordered_map>

#include "cspace/convex_distance.hpp"
#include "cspace/obstacle_grid.hpp"

namespace svmp::cspace {
namespace {

// Above this many obstacles the broadphase grid beats testing bounding boxes one by one.
constexpr size_t kBroadphaseThreshold = 8;

std::shared_ptr<fcl::CollisionGeometryd> makeGeometry(const robots::Shape& s) {
  switch (s.kind) {
    case robots::ShapeKind::kBox: return std::make_shared<fcl::Boxd>(s.dims.x(), s.dims.y(), s.dims.z());
    case robots::ShapeKind::kSphere: return std::make_shared<fcl::Sphered>(s.dims.x());
    case robots::ShapeKind::kCylinder: return std::make_shared<fcl::Cylinderd>(s.dims.x(), s.dims.y());
    case robots::ShapeKind::kCapsule: return std::make_shared<fcl::Capsuled>(s.dims.x(), s.dims.y());
  }
  throw std::logic_error("unknown shape kind");
}

std::atomic<std::uint64_t> next_instance_id{1};

// A shape where it stands. Its world pose and bounding box are kept here, so that pairs are culled
// inline: FCL's AABB tests are calls into its shared library, a third of a check of the Panda among
// 8 boards. Its FCL object is placed only when FCL is asked: for a pair our GJK leaves undecided.
struct Placed {
  const robots::Shape* shape = nullptr;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  Eigen::AlignedBox3d box;
  fcl::CollisionObjectd* object = nullptr;
  bool object_placed = false;  // object's transform is pose

  void place(const Eigen::Isometry3d& world) {
    pose = world;
    box = shape->boundsAt(world);
    object_placed = false;
  }
  fcl::CollisionObjectd* fclObject() {
    if (!object_placed) {
      object->setTransform(pose.linear(), pose.translation());
      object->computeAABB();
      object_placed = true;
    }
    return object;
  }
};

}  // namespace

struct CollisionChecker::Workspace {
  robots::Poses poses;
  // links[i] owns link i's FCL objects; parts[i] places them.
  std::vector<std::vector<std::unique_ptr<fcl::CollisionObjectd>>> links;
  std::vector<std::vector<Placed>> parts;
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> obstacles;  // index = id - 1
  std::vector<Placed> obstacle_parts;                              // index = id - 1
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> base;       // robots::Robot::baseShapes, placed once
  std::vector<Placed> base_parts;

  std::vector<Placed>& partsOf(int link) { return link == robots::Robot::kBase ? base_parts : parts[link]; }
};

CollisionChecker::CollisionChecker(std::shared_ptr<const robots::Robot> robot,
                                   std::shared_ptr<const Environment> env, bool self_collision)
    : robot_(std::move(robot)), env_(std::move(env)), instance_id_(next_instance_id++) {
  if (!robot_ || !env_) throw std::invalid_argument("collision checker: robot and environment required");
  if (env_->obstacles().size() > kBroadphaseThreshold) {
    std::vector<Eigen::AlignedBox3d> boxes;  // index = id - 1
    for (const auto& o : env_->obstacles()) boxes.push_back(o.shape.boundsAt(o.shape.pose));
    grid_ = std::make_unique<const ObstacleGrid>(boxes);
  }
  if (!self_collision) return;
  // Drop pairs that touch in every sampled configuration: they are joined by construction.
  auto candidates = robot_->nonAdjacentLinkPairs();
  std::vector<int> touching(candidates.size(), 0);
  std::mt19937_64 rng(12345);
  constexpr int kSamples = 100;
  Workspace& ws = workspace();
  Eigen::VectorXd q(robot_->dof());
  for (int s = 0; s < kSamples; ++s) {
    for (int i = 0; i < q.size(); ++i)
      q[i] = std::uniform_real_distribution<double>(robot_->lowerLimits()[i],
                                                    robot_->upperLimits()[i])(rng);
    placeRobot(ws, q);
    for (size_t p = 0; p < candidates.size(); ++p)
      touching[p] += linksCollide(ws, candidates[p].first, candidates[p].second);
  }
  // The base and the first link with shapes meet at joint 1: touching there is no news.
  const auto at_joint_1 = std::find_if(candidates.begin(), candidates.end(),
                                       [](const auto& pair) { return pair.first == robots::Robot::kBase; });
  for (size_t p = 0; p < candidates.size(); ++p)
    if (touching[p] < kSamples)
      self_pairs_.push_back(candidates[p]);
    else if (candidates.begin() + p != at_joint_1)
      dropped_pairs_.push_back(candidates[p]);
}

CollisionChecker::~CollisionChecker() = default;

std::unique_ptr<CollisionChecker::Workspace> CollisionChecker::makeWorkspace() const {
  auto ws = std::make_unique<Workspace>();
  ws->links.resize(robot_->numLinks());
  ws->parts.resize(robot_->numLinks());
  for (int i = 0; i < robot_->numLinks(); ++i)
    for (const auto& shape : robot_->linkShapes(i)) {
      ws->links[i].push_back(std::make_unique<fcl::CollisionObjectd>(makeGeometry(shape)));
      Placed part;
      part.shape = &shape;
      part.object = ws->links[i].back().get();
      ws->parts[i].push_back(part);
    }
  const auto placeFixed = [](const robots::Shape& shape, std::vector<std::unique_ptr<fcl::CollisionObjectd>>& objects,
                             std::vector<Placed>& parts) {
    auto obj = std::make_unique<fcl::CollisionObjectd>(makeGeometry(shape), shape.pose.linear(),
                                                       shape.pose.translation());
    obj->computeAABB();
    Placed part;
    part.shape = &shape;
    part.object = obj.get();
    part.place(shape.pose);
    part.object_placed = true;
    parts.push_back(part);
    objects.push_back(std::move(obj));
  };
  for (const auto& o : env_->obstacles()) placeFixed(o.shape, ws->obstacles, ws->obstacle_parts);
  for (const auto& shape : robot_->baseShapes()) placeFixed(shape, ws->base, ws->base_parts);
  return ws;
}

CollisionChecker::Workspace& CollisionChecker::workspace() const {
  // Per-thread cache keyed by this checker's unique id (never reused, so no dangling hits).
  thread_local std::unordered_map<std::uint64_t, Workspace*> cache;
  auto it = cache.find(instance_id_);
  if (it != cache.end()) return *it->second;
  auto ws = makeWorkspace();
  Workspace* raw = ws.get();
  {
    std::lock_guard<std::mutex> lock(workspaces_mutex_);
    workspaces_.push_back(std::move(ws));
  }
  cache.emplace(instance_id_, raw);
  return *raw;
}

void CollisionChecker::placeRobot(Workspace& ws, const Eigen::Ref<const Eigen::VectorXd>& q) const {
  robot_->linkPoses(q, ws.poses);
  for (int i = 0; i < robot_->numLinks(); ++i)
    for (Placed& part : ws.parts[i]) part.place(ws.poses[i] * part.shape->pose);
}

namespace {

// The narrow phase: a GJK run of our own decides (cspace/convex_distance.hpp: 0.24 us for a link
// capsule near a board against FCL's 0.48-0.64, BM_CapsuleBoxCollide), FCL where the run cannot.
bool shapesCollide(Placed& a, Placed& b) {
  if (const auto decided = intersects(*a.shape, a.pose, *b.shape, b.pose)) return *decided;
  fcl::CollisionRequestd request;
  fcl::CollisionResultd result;
  return fcl::collide(a.fclObject(), b.fclObject(), request, result) > 0;
}

// A pair outside the broadphase: bounding boxes first, then the narrow phase.
bool pairCollides(Placed& a, Placed& b) { return a.box.intersects(b.box) && shapesCollide(a, b); }

// A lower bound on the distance between two placed shapes, 0 when they may touch: a separating
// plane's, from a GJK run of our own (cspace/convex_distance.hpp) stopped within `rel_gap` of the
// distance, or once beyond `least` (the callers keep the least over pairs, so the result is the
// same). FCL's distance is not asked: its GJK overestimates, so its value could only serve as a
// first direction, and it cost more than the whole run of ours.
double objectDistance(const Placed& a, const Placed& b, double rel_gap, double least) {
  return std::max(0.0, distanceLowerBound(*a.shape, a.pose, *b.shape, b.pose,
                                          a.pose.translation() - b.pose.translation(), rel_gap, least));
}

// The distance between the bounding boxes: no closer than the shapes.
double boxDistance(const Placed& a, const Placed& b) { return std::sqrt(a.box.squaredExteriorDistance(b.box)); }

}  // namespace

bool CollisionChecker::linksCollide(Workspace& ws, int a, int b) const {
  for (Placed& pa : ws.partsOf(a))
    for (Placed& pb : ws.partsOf(b))
      if (pairCollides(pa, pb)) return true;
  return false;
}

const std::pair<int, int>* CollisionChecker::collidingSelfPair(Workspace& ws) const {
  for (const auto& pair : self_pairs_)
    if (linksCollide(ws, pair.first, pair.second)) return &pair;
  return nullptr;
}

int CollisionChecker::checkImpl(const Eigen::Ref<const Eigen::VectorXd>& q, bool include_virtual) const {
  // A wrong size would read past the limit vectors and the FK loops; NaN is left to withinLimits.
  if (q.size() != robot_->dof()) robot_->checkConfiguration(q, "collision check");
  checks_.fetch_add(1, std::memory_order_relaxed);
  if (!robot_->withinLimits(q)) return kJointLimitHit;
  Workspace& ws = workspace();
  placeRobot(ws, q);
  int lowest = std::numeric_limits<int>::max();
  for (int i = 0; i < robot_->numLinks(); ++i) {
    for (Placed& part : ws.parts[i]) {
      const auto consider = [&](int index) {  // index = id - 1
        const Obstacle& o = env_->obstacles()[index];
        if (o.id < lowest && (include_virtual || !o.is_virtual) && pairCollides(part, ws.obstacle_parts[index]))
          lowest = o.id;
      };
      if (grid_)
        grid_->forEachCandidate(part.box, consider);
      else  // ids ascend: none past the lowest hit so far can lower it
        for (int index = 0; index < std::ssize(env_->obstacles()) && index + 1 < lowest; ++index) consider(index);
    }
  }
  if (lowest != std::numeric_limits<int>::max()) return lowest;
  return collidingSelfPair(ws) ? kSelfCollisionHit : kFree;
}

bool CollisionChecker::hits(const Eigen::Ref<const Eigen::VectorXd>& q, int id) const {
  if (q.size() != robot_->dof()) robot_->checkConfiguration(q, "collision check");
  checks_.fetch_add(1, std::memory_order_relaxed);
  if (!robot_->withinLimits(q)) return false;
  Workspace& ws = workspace();
  placeRobot(ws, q);
  if (id == kSelfCollisionHit) return collidingSelfPair(ws) != nullptr;
  Placed& obstacle = ws.obstacle_parts.at(id - 1);
  for (int i = 0; i < robot_->numLinks(); ++i)
    for (Placed& part : ws.parts[i])
      if (pairCollides(part, obstacle)) return true;
  return false;
}

std::vector<int> CollisionChecker::allHits(const Eigen::Ref<const Eigen::VectorXd>& q, bool include_virtual) const {
  if (q.size() != robot_->dof()) robot_->checkConfiguration(q, "collision check");
  checks_.fetch_add(1, std::memory_order_relaxed);
  std::vector<int> ids;
  if (!robot_->withinLimits(q)) return ids;
  Workspace& ws = workspace();
  placeRobot(ws, q);
  std::vector<char> hit(env_->obstacles().size(), 0);
  for (int i = 0; i < robot_->numLinks(); ++i)
    for (Placed& part : ws.parts[i]) {
      const auto consider = [&](int index) {  // index = id - 1
        if (!hit[index] && (include_virtual || !env_->obstacles()[index].is_virtual) &&
            pairCollides(part, ws.obstacle_parts[index]))
          hit[index] = 1;
      };
      if (grid_)
        grid_->forEachCandidate(part.box, consider);
      else
        for (int index = 0; index < std::ssize(env_->obstacles()); ++index) consider(index);
    }
  for (size_t index = 0; index < hit.size(); ++index)
    if (hit[index]) ids.push_back(static_cast<int>(index) + 1);
  if (collidingSelfPair(ws)) ids.push_back(kSelfCollisionHit);
  return ids;
}

std::optional<std::pair<int, int>> CollisionChecker::selfCollidingPair(const Eigen::Ref<const Eigen::VectorXd>& q) const {
  robot_->checkConfiguration(q, "collision check");
  checks_.fetch_add(1, std::memory_order_relaxed);
  Workspace& ws = workspace();
  placeRobot(ws, q);
  if (const auto* pair = collidingSelfPair(ws)) return *pair;
  return std::nullopt;
}

double CollisionChecker::clearance(const Eigen::Ref<const Eigen::VectorXd>& q) const {
  robot_->checkConfiguration(q, "clearance");
  distances_.fetch_add(1, std::memory_order_relaxed);
  Workspace& ws = workspace();
  placeRobot(ws, q);
  // Each pair's distance from our GJK to within 1e-6 of it (from below), pairs whose bounding boxes
  // are farther apart than the best so far skipped: FCL's distance overestimated by more than 1e-6 in
  // 12% of capsule-box and 19% of box-box cases (certification_test).
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i < robot_->numLinks(); ++i)
    for (const Placed& part : ws.parts[i])
      for (const auto& o : env_->obstacles()) {
        const Placed& obstacle = ws.obstacle_parts[o.id - 1];
        if (o.is_virtual || !(boxDistance(part, obstacle) < best)) continue;
        best = std::min(best, objectDistance(part, obstacle, 1e-6, best));
      }
  return best;
}

bool CollisionChecker::freeDistances(const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::VectorXd& cap,
                                     Eigen::VectorXd& d) const {
  robot_->checkConfiguration(q, "free distance");
  if (cap.size() != robot_->numLinks())
    throw std::invalid_argument("free distances: one cap per link, got " + std::to_string(cap.size()));
  distances_.fetch_add(1, std::memory_order_relaxed);
  d = cap;
  if (!robot_->withinLimits(q)) {
    d.setZero();
    return false;
  }
  Workspace& ws = workspace();
  placeRobot(ws, q);
  // The AABBs' distance bounds the shapes' from below: a pair farther than the link's best so far
  // (or its cap) is skipped. Returns true at contact.
  auto touches = [&](int link, const Placed& a, const Placed& b) {
    double& best = d[link];
    // Within 1e-3 of the distance: a looser bound only costs the validator a few more bisections.
    if (boxDistance(a, b) < best) best = std::min(best, objectDistance(a, b, 1e-3, best));
    return best == 0;
  };
  auto anyContact = [&] {
    for (int i = 0; i < robot_->numLinks(); ++i)
      for (const Placed& part : ws.parts[i])
        for (const auto& o : env_->obstacles())
          if (!o.is_virtual && touches(i, part, ws.obstacle_parts[o.id - 1])) return true;
    // A self pair counts for its distal link, whose bound covers its motion relative to the other
    // (the base, kBase, comes first).
    for (const auto& [a, b] : self_pairs_)
      for (const Placed& pa : ws.partsOf(a))
        for (const Placed& pb : ws.partsOf(b))
          if (touches(std::max(a, b), pa, pb)) return true;
    return false;
  };
  const bool contact = anyContact();
  if (contact) d.setZero();
  return !contact;
}

double CollisionChecker::freeDistance(const Eigen::Ref<const Eigen::VectorXd>& q) const {
  thread_local Eigen::VectorXd d;
  const Eigen::VectorXd cap =
      Eigen::VectorXd::Constant(robot_->numLinks(), std::numeric_limits<double>::infinity());
  return freeDistances(q, cap, d) ? d.minCoeff() : 0.0;
}

}  // namespace svmp::cspace
