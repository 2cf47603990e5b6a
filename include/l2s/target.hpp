#pragma once
// The calibration board: a plane with four circular through-holes.

#include <l2s/export.hpp>

#include <Eigen/Core>
#include <array>
#include <optional>
#include <string>
#include <vector>

namespace l2s {

/// Index of a hole in every array of four centres: the paper's labels.
enum class Hole { TopLeft = 0, TopRight = 1, BottomLeft = 2, BottomRight = 3 };

/// The short label of a hole, as in result files and drawings: "TL", "TR", "BL", "BR".
L2S_EXPORT const char* hole_name(Hole hole);

/// ArUco markers printed on the board's front face (DATASET.md, `markers:`),
/// axis-aligned with the board; a mono camera finds the board by them.
struct L2S_EXPORT MarkerLayout {
  std::string dictionary = "DICT_6X6_250";  ///< OpenCV's predefined dictionary name (DICT_4X4_50 ... DICT_ARUCO_ORIGINAL)
  double size = 0.20;                        ///< [m] side of the black square
  std::vector<int> ids;                      ///< one per marker, unique, < the dictionary's size
  std::vector<Eigen::Vector2d> centres;      ///< [m] board frame x y (z = 0), one per id

  /// The default marker board's layout: four 0.2 m DICT_6X6_250 markers,
  /// ids 1..4, near the corners of the 1.4 x 1.0 m board.
  static MarkerLayout corners_default();

  /// Corners of marker `index` in the board frame (z = 0), in ArUco's order:
  /// top-left, top-right, bottom-right, bottom-left as seen from the front.
  std::array<Eigen::Vector3d, 4> corners(std::size_t index) const;

  /// Bits per side of the dictionary's markers (4..7), 0 for an unknown name.
  static int dictionary_bits(const std::string& name);
  /// Markers in the dictionary (ids run 0..count-1), 0 for an unknown name.
  static int dictionary_size(const std::string& name);
};

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
  std::optional<MarkerLayout> markers;  ///< printed ArUco markers, when the board carries them (mono cameras need them)

  /// The board of the 2017 paper: 1.2 x 0.8 x 0.02 m, r 0.12 m, 0.3 x 0.3 m pattern.
  static Target paper2017();
  /// The default board with the default markers (MarkerLayout::corners_default).
  static Target with_default_markers();
  /// A preset by name: "default", "markers" (with_default_markers) or
  /// "paper2017"; throws ParamError otherwise.
  static Target preset(const std::string& name);

  /// Hole centres in the board frame (z = 0), ordered as enum Hole.
  std::array<Eigen::Vector2d, 4> hole_centers() const;

  /// Throws ParamError naming the field when the geometry is impossible
  /// (non-positive sizes, holes overlapping or leaving the board; markers
  /// ("markers.size", "markers.ids", "markers.centres", "markers.dictionary")
  /// of an unknown dictionary, off the board, over a hole or overlapping).
  void validate() const;
};

}  // namespace l2s
