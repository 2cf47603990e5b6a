#pragma once
// The board of a randomised scene, drawn apart from the rest of the scene
// (each from a generator of its own, so that a seed's rig, light, lidar and
// geometry stay as they were): its face, its markers and its size and holes.

#include <l2s/export.hpp>
#include <l2s/sim/appearance.hpp>
#include <l2s/target.hpp>

#include <random>

namespace l2s::sim {

/// Which boards randomised scenes draw (make_random_scene).
enum class BoardDraw {
  /// every face, markers, size and hole layout (the draws below), and the
  /// rigs and mountings of mounting_draw.hpp
  All,
  Classic,  ///< the default board without markers, matte, wood or low-contrast, a level rig of the common
            ///< sizes, an upright lidar: each seed's scene as drawn before the other boards existed
  /// every face, size and hole layout and rig of All, always with markers,
  /// the rig level and the lidar upright: what the stereo branch's marker
  /// pose is measured on
  Marked,
};

/// Draws the board's face over `look`: in about half the draws one of the
/// faces users print or paint (speckle, noise print, chipboard, black before
/// a bright wall, white, often before a white wall, logo and label, sticker,
/// glossy), otherwise `look`'s face as drawn.
L2S_SIM_EXPORT void draw_board_face(std::mt19937_64& faces, Appearance* look);

/// Draws the board's size and holes into `target`: in about 40 % of the
/// draws a board of 0.8-1.6 x 0.6-1.2 m with holes of 0.06-0.15 m radius on
/// a rectangle of its own (e.g. 1.2 x 0.9 m, r 0.10 m on 0.60 x 0.45 m),
/// always a valid target; otherwise the default board.
L2S_SIM_EXPORT void draw_board_geometry(std::mt19937_64& geometry, Target* target);

/// Draws printed ArUco markers for `target`'s board: in a share `share` of
/// the draws (about a third by default) four markers near its corners (the
/// default layout where it fits the board, else one of the board's own),
/// 0.15-0.2 m (smaller where the board has no room), of one of OpenCV's
/// dictionaries (4x4 to 7x7 bits, and the original ArUco), with distinct
/// random ids; otherwise none. The same generator state gives the same
/// markers whatever `share`, where it gives markers.
L2S_SIM_EXPORT void draw_board_markers(std::mt19937_64& markers, Target* target, double share = 1.0 / 3.0);

}  // namespace l2s::sim
