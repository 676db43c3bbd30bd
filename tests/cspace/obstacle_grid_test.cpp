// The broadphase grid (cspace/obstacle_grid.hpp) against brute force: every box that overlaps a
// query box is visited, touching included, and none twice, for small and large boxes in 2-D-like
// (flat) and 3-D layouts, query boxes from points to larger than the whole layout.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "cspace/obstacle_grid.hpp"

namespace svmp::cspace {
namespace {

Eigen::AlignedBox3d randomBox(std::mt19937_64& rng, double spread, double largest, bool flat) {
  std::uniform_real_distribution<double> unit(0, 1);
  const Eigen::Vector3d centre(spread * unit(rng), spread * unit(rng), flat ? 0.0 : spread * unit(rng));
  // Sizes spread over three orders of magnitude, so that some boxes span many cells.
  const Eigen::Vector3d half =
      0.5 * largest * Eigen::Vector3d(std::pow(1e-3, unit(rng)), std::pow(1e-3, unit(rng)),
                                      flat ? 1.0 : std::pow(1e-3, unit(rng)));
  return {centre - half, centre + half};
}

TEST(ObstacleGrid, VisitsEveryOverlappingBoxOnce) {
  std::mt19937_64 rng(8);
  for (const bool flat : {true, false})
    for (const int count : {9, 60, 500}) {
      std::vector<Eigen::AlignedBox3d> boxes;
      for (int i = 0; i < count; ++i) boxes.push_back(randomBox(rng, 10, 3, flat));
      const ObstacleGrid grid(boxes);
      EXPECT_GT(grid.numCells(), count);  // a grid, not one cell
      int overlaps = 0, visits = 0;
      for (int trial = 0; trial < 400; ++trial) {
        Eigen::AlignedBox3d query = randomBox(rng, 12, trial % 50 == 0 ? 30 : 2, flat);
        if (trial % 7 == 0) {  // touching a box exactly, face to face
          const Eigen::AlignedBox3d& b = boxes[trial % count];
          query = Eigen::AlignedBox3d(Eigen::Vector3d(b.max().x(), b.min().y(), b.min().z()),
                                      Eigen::Vector3d(b.max().x() + 0.5, b.max().y(), b.max().z()));
        }
        std::vector<int> seen(count, 0);
        grid.forEachCandidate(query, [&](int i) { ++seen[i]; });
        for (int i = 0; i < count; ++i) {
          EXPECT_LE(seen[i], 1) << "box " << i << " visited twice";
          if (boxes[i].intersects(query)) {
            EXPECT_EQ(seen[i], 1) << "overlapping box " << i << " missed";
            ++overlaps;
          }
          visits += seen[i];
        }
      }
      EXPECT_GT(overlaps, 40);  // the comparison is not vacuous
      // Not every box for every query: the grid culls.
      EXPECT_LT(visits, 400 * count / 4) << count << " boxes";
    }
}

TEST(ObstacleGrid, RejectsNoBoxesAndUnboundedOnes) {
  EXPECT_THROW(ObstacleGrid({}), std::invalid_argument);
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_THROW(ObstacleGrid({Eigen::AlignedBox3d(Eigen::Vector3d::Zero(), Eigen::Vector3d(inf, 1, 1))}),
               std::invalid_argument);
}

}  // namespace
}  // namespace svmp::cspace
