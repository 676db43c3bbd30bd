#pragma once
// The workspace: obstacles as FCL primitives with a world pose, an id (>= 1; the collision checker
// returns it), an optional `virtual` flag for guide obstacles that may be touched (thesis ch. 2.3) and
// a class weight that scales the SVM penalty C of that obstacle's samples (thesis ch. 4.1.2).
// Thread safety: immutable after construction; const methods may run concurrently.
#include <optional>
#include <string>
#include <vector>

#include "robots/shape.hpp"

namespace svmp::cspace {

struct Obstacle {
  int id = 0;
  std::string name;
  robots::Shape shape;  // pose in the world frame
  bool is_virtual = false;
  double weight = 1.0;
  // A configuration in collision with this obstacle, to root its sampling tree (thesis Algorithm 1);
  // found automatically when absent.
  std::optional<Eigen::VectorXd> root_sample;
};

class Environment {
 public:
  Environment() = default;
  // Ids are assigned 1, 2, ... in order. Throws std::invalid_argument on an invalid shape or weight.
  explicit Environment(std::vector<Obstacle> obstacles);

  const std::vector<Obstacle>& obstacles() const { return obstacles_; }
  int size() const { return static_cast<int>(obstacles_.size()); }
  // Obstacle with that id; throws std::out_of_range when there is none.
  const Obstacle& byId(int id) const;
  int numReal() const;
  // Per obstacle (index id - 1), the smallest id of the real obstacles it is joined to by a chain of
  // real obstacles one inside another (a shape given twice, boxes nested; its own id when none;
  // virtual obstacles keep theirs): one region of C-space. Obstacles that only overlap or touch, as
  // the pieces of a frame round a window, stay apart. "Inside": the shape's support points along the
  // 26 directions of the world's, its own and the other's axes (its corners, for a box) lie in the
  // other shape, within 1e-9 of its size (exact where either is a box; a round shape in a round one
  // may poke out by about 3% of its size). Sweep over the x extents, so far-apart obstacles cost little.
  std::vector<int> nestedGroups() const;
  // Per obstacle (index id - 1), 1 when it lies inside another real obstacle of its group (of
  // `groups`, nestedGroups()'s) that is itself kept, exactly so (either is a box, or the two are the
  // same shape), and has no `sample:`: its C-region is that one's too, so sampling it adds nothing. A
  // shape given n times keeps its lowest id; of nested ones the outermost is kept. Members are taken
  // largest bounding box first, each tested against those kept so far.
  std::vector<char> innerObstacles(const std::vector<int>& groups) const;

 private:
  std::vector<Obstacle> obstacles_;
};

}  // namespace svmp::cspace
