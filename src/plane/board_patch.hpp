#pragma once
// The largest connected patch of a plane's consensus, measured in the plane
// (private; used by PlaneSegmenter to tell the board from walls).

#include "plane/plane_fit.hpp"

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <unordered_set>
#include <vector>

namespace l2s::detail {

/// A 2D grid on a plane: cells of gap_u (horizontal) x gap_v (vertical), so that
/// two points less than one cell apart along each axis land in touching cells.
class PlaneGrid {
 public:
  PlaneGrid(const Plane& plane, const Eigen::Vector3d& axis, double gap_u, double gap_v);
  Eigen::Vector2d to_plane(const Eigen::Vector3d& p) const;  ///< (right, up) [m]
  Eigen::Vector2i index(const Eigen::Vector2d& uv) const;  ///< (column, row) of the cell holding uv
  std::uint64_t cell(const Eigen::Vector2d& uv) const;       ///< the same, packed as a hash key
  std::uint64_t neighbour(std::uint64_t cell, int du, int dv) const;

 private:
  PlaneAxes axes_;
  Eigen::Vector3d origin_;
  double inv_u_, inv_v_;
};

/// The cells of a patch that lie in its box. Membership is asked for every
/// point of a dense cloud near the plane, so it is a flat bitmap over the
/// box's cells; a box too large for one (a long sparse component of junk)
/// keeps a hash set instead.
class PatchCells {
 public:
  /// `box_cells`: the (column, row) range of cells that the box covers.
  PatchCells(const Eigen::AlignedBox2i& box_cells, const std::vector<Eigen::Vector2i>& cells);
  PatchCells() = default;
  /// Whether `cell`, one of the box's cells, belongs to the patch.
  bool contains(const Eigen::Vector2i& cell) const;

 private:
  Eigen::Vector2i origin_ = Eigen::Vector2i::Zero();
  int columns_ = 0;
  std::vector<std::uint8_t> dense_;            // row-major over the box's cells
  std::unordered_set<std::uint64_t> sparse_;   // when the box has too many cells for a bitmap
};

struct Patch {
  PatchCells cells;                         ///< grid cells of the patch inside its box
  Eigen::AlignedBox2d box;                  ///< in-plane (right, up) region of the board within the patch
  std::size_t points = 0;                   ///< sample points in it (inside box)
  double extent_long = 0.0;                 ///< [m] smallest enclosing rectangle, longer side
  double extent_short = 0.0;                ///< [m] shorter side
};

/// Largest 8-connected group of occupied cells among `points` (already on the
/// plane). When a window of `window` size (right, up) holds at least
/// `window_share` of it, the patch is cut to that window: the board plane also
/// meets the ground (and clutter) along thin lines that can touch the board.
Patch largest_patch(const PlaneGrid& grid, const std::vector<Eigen::Vector3d>& points,
                    const Eigen::Vector2d& window, double window_share);

/// Is the point in the patch (cell and box)? In the plane's (right, up), or in 3D.
bool in_patch(const PlaneGrid& grid, const Patch& patch, const Eigen::Vector2d& uv);
bool in_patch(const PlaneGrid& grid, const Patch& patch, const Eigen::Vector3d& p);

}  // namespace l2s::detail
