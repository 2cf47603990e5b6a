#pragma once
// Where the holes not found yet should be, from holes already found and the
// known hole pattern (private to the library). A ring-free lidar's field of
// view can cut the board through a hole: that hole opens onto the unscanned
// outside and is no longer a closed gap in the board's occupancy, but two
// holes found at the pattern's spacing say where it is.

#include <Eigen/Core>
#include <vector>

namespace l2s::detail {

/// Every place the pattern puts a hole when two of `found` (in-plane, [m])
/// are two of its holes: a pair `spacing_x` or `spacing_y` apart (within
/// `tolerance`) is a side of the pattern's rectangle, the other side either
/// way across; a pair a diagonal apart is a diagonal, in either mirror image.
/// Places may repeat or coincide with found holes: the caller verifies each.
std::vector<Eigen::Vector2d> predicted_holes(const std::vector<Eigen::Vector2d>& found,
                                             double spacing_x, double spacing_y, double tolerance);

}  // namespace l2s::detail
