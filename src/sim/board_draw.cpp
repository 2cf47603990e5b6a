// Sizes are those of boards users make: 0.8-1.6 m wide, holes of 6-15 cm
// radius (the paper's 12 cm among them) kept 5 cm from the board's edges and
// 10 cm apart; markers where users print them, near the corners.

#include <l2s/sim/board_draw.hpp>

#include <l2s/error.hpp>

#include "sim/draw_random.hpp"

#include <algorithm>
#include <array>

namespace l2s::sim {

using detail::chance;
using detail::pick;
using detail::uniform;

void draw_board_face(std::mt19937_64& faces, Appearance* look) {
  if (!chance(faces, 0.5)) return;
  constexpr std::array<BoardTexture, 8> kFaces{BoardTexture::Speckle, BoardTexture::NoisePrint,
                                               BoardTexture::Chipboard, BoardTexture::Black,
                                               BoardTexture::White, BoardTexture::Logo,
                                               BoardTexture::Sticker, BoardTexture::Glossy};
  look->board = kFaces[pick(faces, std::array<double, 8>{1, 1, 1, 1, 1, 1, 1, 1})];
  // A black board is drawn where users meet it: before a bright wall, the
  // board's edges darker than their surround.
  if (look->board == BoardTexture::Black && look->background == Background::Textured)
    look->background = chance(faces, 0.5) ? Background::Plain : Background::White;
  // A white board is often hung before a white wall.
  if (look->board == BoardTexture::White && chance(faces, 0.5)) look->background = Background::White;
}

void draw_board_geometry(std::mt19937_64& geometry, Target* target) {
  if (!chance(geometry, 0.4)) return;
  // Margins real boards keep: 5 cm of board around each hole, 10 cm between
  // two holes' rims.
  for (int attempt = 0; attempt < 50; ++attempt) {
    Target board = *target;
    board.board_width = uniform(geometry, 0.8, 1.6);
    board.board_height = uniform(geometry, 0.6, std::min(1.2, board.board_width));
    board.hole_radius = uniform(geometry, 0.06, std::min(0.15, 0.2 * board.board_height));
    const double r = board.hole_radius;
    const double max_x = board.board_width - 2.0 * r - 0.1, max_y = board.board_height - 2.0 * r - 0.1;
    const double min_x = 2.0 * r + 0.1, min_y = 2.0 * r + 0.1;
    if (max_x < min_x || max_y < min_y) continue;
    board.hole_spacing_x = uniform(geometry, std::max(min_x, 0.35 * board.board_width), max_x);
    board.hole_spacing_y = uniform(geometry, std::max(min_y, 0.35 * board.board_height), max_y);
    board.markers.reset();
    try {
      board.validate();
    } catch (const ParamError&) {
      continue;
    }
    *target = board;
    return;
  }
}

void draw_board_markers(std::mt19937_64& markers, Target* target, double share) {
  if (!chance(markers, share)) return;
  constexpr std::array<const char*, 8> kDictionaries{"DICT_4X4_50",  "DICT_4X4_100",  "DICT_5X5_100",
                                                     "DICT_5X5_250", "DICT_6X6_250",  "DICT_6X6_1000",
                                                     "DICT_7X7_100", "DICT_ARUCO_ORIGINAL"};
  MarkerLayout layout = MarkerLayout::corners_default();
  layout.dictionary = kDictionaries[pick(markers, std::array<double, 8>{1, 1, 1, 1, 1, 1, 1, 1})];
  layout.size = uniform(markers, 0.15, 0.20);
  const int count = MarkerLayout::dictionary_size(layout.dictionary);
  layout.ids.clear();
  while (layout.ids.size() < layout.centres.size()) {
    const int id = static_cast<int>(uniform(markers, 0.0, count - 1e-9));
    if (std::find(layout.ids.begin(), layout.ids.end(), id) == layout.ids.end()) layout.ids.push_back(id);
  }
  // Where the default centres do not fit the board, the markers go into its
  // corners, 3 cm in from the edges, as small as they must to clear the holes.
  for (int attempt = 0; attempt < 12; ++attempt) {
    target->markers = layout;
    try {
      target->validate();
      return;
    } catch (const ParamError&) {
    }
    if (attempt > 0) layout.size *= 0.85;
    const double x = 0.5 * target->board_width - 0.03 - 0.5 * layout.size;
    const double y = 0.5 * target->board_height - 0.03 - 0.5 * layout.size;
    layout.centres = {Eigen::Vector2d(-x, y), Eigen::Vector2d(x, y), Eigen::Vector2d(-x, -y), Eigen::Vector2d(x, -y)};
  }
  target->markers.reset();  // no room on this board
}

}  // namespace l2s::sim
