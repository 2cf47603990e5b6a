// The largest connected patch of a plane and the lookup of its cells: the
// flat bitmap over a board-sized box and the hash set kept for boxes too
// large for one must answer alike.
#include "plane/board_patch.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace l2s::detail {
namespace {

// The plane x = 3 in a frame with z up: in-plane u runs along -y, v along z.
const Plane kPlane(Eigen::Vector3d(-1.0, 0.0, 0.0), Eigen::Vector3d(3.0, 0.0, 0.0));
const Eigen::Vector3d kUp = Eigen::Vector3d::UnitZ();
constexpr double kGap = 0.1;

Eigen::Vector3d on_plane(double u, double v) { return {3.0, -u, v}; }

TEST(BoardPatch, BoardWithHoleKeepsItsCellsAndNotTheHole) {
  std::vector<Eigen::Vector3d> points;
  for (double u = 0.0; u < 1.2; u += 0.02)
    for (double v = 0.0; v < 0.8; v += 0.02)
      if ((Eigen::Vector2d(u, v) - Eigen::Vector2d(0.6, 0.4)).norm() > 0.25) points.push_back(on_plane(u, v));
  const PlaneGrid grid(kPlane, kUp, kGap, kGap);
  const Patch patch = largest_patch(grid, points, {1.5, 1.0}, 0.9);
  EXPECT_NEAR(patch.extent_long, 1.18, 0.03);
  EXPECT_NEAR(patch.extent_short, 0.78, 0.03);
  for (const Eigen::Vector3d& p : points) ASSERT_TRUE(in_patch(grid, patch, p));
  // The hole's centre cells hold no point; a point beside the board is outside the box.
  EXPECT_FALSE(in_patch(grid, patch, on_plane(0.62, 0.42)));
  EXPECT_FALSE(in_patch(grid, patch, on_plane(2.0, 0.4)));
}

TEST(BoardPatch, HugeSparseComponentFallsBackToHashedCells) {
  // A diagonal chain of touching cells 400 m long: its box spans 16M cells,
  // too many for a bitmap.
  std::vector<Eigen::Vector3d> points;
  for (int k = 0; k < 4000; ++k) points.push_back(on_plane(0.1 * k + 0.05, 0.1 * k + 0.05));
  const PlaneGrid grid(kPlane, kUp, kGap, kGap);
  const Patch patch = largest_patch(grid, points, {1.5, 1.0}, 0.9);
  EXPECT_EQ(patch.points, points.size());
  for (const Eigen::Vector3d& p : points) ASSERT_TRUE(in_patch(grid, patch, p));
  EXPECT_FALSE(in_patch(grid, patch, on_plane(200.05, 100.05)));  // inside the box, off the chain
}

}  // namespace
}  // namespace l2s::detail
