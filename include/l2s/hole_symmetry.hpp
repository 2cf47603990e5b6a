#pragma once
// The in-plane turns that map the board's hole pattern onto itself, as
// relabellings of the four holes. A sensor labels holes by its own "up"
// (lidar +z, camera optical -y), so a sensor rolled by 180 deg against the
// other, or by about 90 deg over a square pattern, labels the same physical
// hole differently: the labellings then differ by one of these turns. The
// four centres alone cannot tell them apart (they fit equally well); the
// scene can (calibration_check.hpp).

#include <l2s/geometry.hpp>
#include <l2s/export.hpp>
#include <l2s/target.hpp>

#include <array>
#include <vector>

namespace l2s {

/// A relabelling of the four holes: relabelled[h] = centers[permutation[h]]
/// (indices in enum Hole order).
using HolePermutation = std::array<int, 4>;

/// One turn of the pattern in its own plane.
struct L2S_EXPORT HoleSymmetry {
  int degrees = 0;  ///< [deg] 0, 90, 180 or 270, counter-clockwise seen from the front
  HolePermutation permutation{{0, 1, 2, 3}};  ///< the labels a sensor seeing the board turned by `degrees` gives
};

/// The four turns of a four-hole pattern by quarter turns (0, 90, 180, 270
/// deg), whatever its spacing; a rectangle maps onto itself only under 0 and 180.
L2S_EXPORT std::vector<HoleSymmetry> quarter_turns();

/// The turns that map this target's pattern onto itself, identity first:
/// 0 and 180 deg for a rectangle, all four for a square (spacings within
/// `tolerance` [m] of each other).
L2S_EXPORT std::vector<HoleSymmetry> hole_symmetries(const Target& target, double tolerance = 1e-3);

/// Centres relabelled by `permutation`.
L2S_EXPORT HoleCenters relabel(const HoleCenters& centers, const HolePermutation& permutation);

}  // namespace l2s
