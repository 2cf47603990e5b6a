#pragma once
// The calibration board: a plane with four circular through-holes.

#include <l2s/export.hpp>

#include <Eigen/Core>
#include <array>
#include <string>

namespace l2s {

/// Index of a hole in every array of four centres: the paper's labels.
enum class Hole { TopLeft = 0, TopRight = 1, BottomLeft = 2, BottomRight = 3 };

/// The short label of a hole, as in result files and drawings: "TL", "TR", "BL", "BR".
L2S_EXPORT const char* hole_name(Hole hole);

/// Geometry of the board (DATASET.md, target.yaml). The board frame has its
/// origin at the centre of the front face, x to the right and y up as seen
/// from the sensors, z out of the front face; the solid spans z in [-t, 0].
struct L2S_EXPORT Target {
  double board_width = 1.4;     ///< [m] outer size, long side horizontal
  double board_height = 1.0;    ///< [m]
  double board_thickness = 0.02;  ///< [m]
  double hole_radius = 0.12;    ///< [m]
  double hole_spacing_x = 0.5;  ///< [m] between hole centres, horizontally
  double hole_spacing_y = 0.4;  ///< [m] between hole centres, vertically

  /// The board of the 2017 paper: 1.2 x 0.8 x 0.02 m, r 0.12 m, 0.3 x 0.3 m pattern.
  static Target paper2017();
  /// A preset by name: "default" or "paper2017"; throws ParamError otherwise.
  static Target preset(const std::string& name);

  /// Hole centres in the board frame (z = 0), ordered as enum Hole.
  std::array<Eigen::Vector2d, 4> hole_centers() const;

  /// Throws ParamError naming the field when the geometry is impossible
  /// (non-positive sizes, holes overlapping or leaving the board).
  void validate() const;
};

}  // namespace l2s
