#pragma once
// The collision checker's broadphase over many static obstacles: a uniform grid over their bounding
// boxes (Ericson, *Real-Time Collision Detection*, 7.1). Each cell lists the boxes that meet it, so
// a query box visits a few cells and tests a few boxes. It replaced FCL's dynamic AABB tree, whose
// traversal (calls into FCL's shared library per node) was a quarter of an arm's run among 60 small
// boxes (docs/benchmarks.md, "The broadphase grid").
//
// A box met by several query cells is reported once: in the cell at the low corner of the overlap of
// its cell range with the query's.
//
// Thread safety: immutable after construction; every const method may be called from many threads.
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <vector>

namespace svmp::cspace {

class ObstacleGrid {
 public:
  // About kCellsPerBox cells per box, at most kMaxCellsPerAxis along an axis.
  static constexpr int kCellsPerBox = 4;
  static constexpr int kMaxCellsPerAxis = 64;

  explicit ObstacleGrid(const std::vector<Eigen::AlignedBox3d>& boxes);

  // Calls visit(i) once for each box i whose cells meet `box`: every box that overlaps it, and
  // maybe some that do not (the caller tests the boxes themselves).
  template <class Visit>
  void forEachCandidate(const Eigen::AlignedBox3d& box, Visit&& visit) const {
    if (!box.intersects(bounds_)) return;
    const std::array<int, 3> lo = cellOf(box.min()), hi = cellOf(box.max());
    for (int z = lo[2]; z <= hi[2]; ++z)
      for (int y = lo[1]; y <= hi[1]; ++y)
        for (int x = lo[0]; x <= hi[0]; ++x) {
          const int cell = cellIndex(x, y, z);
          for (int k = cell_start_[cell]; k < cell_start_[cell + 1]; ++k) {
            const int i = entries_[k];
            const std::array<int, 3>& first = first_cell_[i];
            // Reported in the first cell the box and the query share.
            if (x == std::max(lo[0], first[0]) && y == std::max(lo[1], first[1]) && z == std::max(lo[2], first[2]))
              visit(i);
          }
        }
  }

  int numCells() const { return dims_[0] * dims_[1] * dims_[2]; }

 private:
  std::array<int, 3> cellOf(const Eigen::Vector3d& p) const;
  int cellIndex(int x, int y, int z) const { return (z * dims_[1] + y) * dims_[0] + x; }

  Eigen::AlignedBox3d bounds_;
  Eigen::Vector3d cell_size_;
  std::array<int, 3> dims_{1, 1, 1};
  std::vector<int> cell_start_;               // cell c's boxes: entries_[cell_start_[c] .. cell_start_[c + 1])
  std::vector<int> entries_;                  // box indices, ascending within a cell
  std::vector<std::array<int, 3>> first_cell_;  // per box, its lowest cell
};

}  // namespace svmp::cspace
