#include "cspace/obstacle_grid.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace svmp::cspace {

ObstacleGrid::ObstacleGrid(const std::vector<Eigen::AlignedBox3d>& boxes) {
  if (boxes.empty()) throw std::invalid_argument("obstacle grid: no boxes");
  for (const auto& b : boxes) {
    if (b.isEmpty() || !b.min().allFinite() || !b.max().allFinite())
      throw std::invalid_argument("obstacle grid: an empty or unbounded box");
    bounds_.extend(b);
  }
  // Cubic cells, about kCellsPerBox per box over the boxes' bounds.
  const Eigen::Vector3d extent = bounds_.sizes().cwiseMax(1e-12);
  const double volume = extent.prod();
  const double side = std::cbrt(volume / (kCellsPerBox * static_cast<double>(boxes.size())));
  for (int a = 0; a < 3; ++a) {
    dims_[a] = std::clamp(static_cast<int>(std::ceil(extent[a] / side)), 1, kMaxCellsPerAxis);
    cell_size_[a] = extent[a] / dims_[a];
  }
  std::vector<std::vector<int>> cells(numCells());
  first_cell_.resize(boxes.size());
  for (size_t i = 0; i < boxes.size(); ++i) {
    const std::array<int, 3> lo = cellOf(boxes[i].min()), hi = cellOf(boxes[i].max());
    first_cell_[i] = lo;
    for (int z = lo[2]; z <= hi[2]; ++z)
      for (int y = lo[1]; y <= hi[1]; ++y)
        for (int x = lo[0]; x <= hi[0]; ++x) cells[cellIndex(x, y, z)].push_back(static_cast<int>(i));
  }
  cell_start_.assign(1, 0);
  for (const auto& c : cells) {
    entries_.insert(entries_.end(), c.begin(), c.end());
    cell_start_.push_back(static_cast<int>(entries_.size()));
  }
}

std::array<int, 3> ObstacleGrid::cellOf(const Eigen::Vector3d& p) const {
  std::array<int, 3> c{};
  for (int a = 0; a < 3; ++a) {
    const double t = std::floor((p[a] - bounds_.min()[a]) / cell_size_[a]);
    c[a] = static_cast<int>(std::clamp(t, 0.0, static_cast<double>(dims_[a] - 1)));
  }
  return c;
}

}  // namespace svmp::cspace
