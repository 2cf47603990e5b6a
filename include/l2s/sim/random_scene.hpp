#pragma once
// One randomised scene of the `scenes` experiment (issues 7 and 8): the
// camera side (draw_camera_scene: rig, lenses, raw or rectified images, the
// look) and the lidar side (draw_lidar_scene: model and quirks, mounting,
// stand, walls, clutter, board distance; a solid-state lidar's returns kept
// as one accumulated cloud or not) drawn from one seed and composed
// into one simulation. A draw whose board cannot be placed for both sensors
// is drawn again from the next derived seed, so every seed gives a scene.

#include <l2s/export.hpp>
#include <l2s/sim/board_draw.hpp>
#include <l2s/sim/simulation.hpp>

#include <cstdint>
#include <memory>
#include <string>

namespace l2s::sim {

struct RandomScene {
  std::uint64_t seed = 0;    ///< the seed asked for
  int redraws = 0;           ///< draws rejected before this one (board could not be placed)
  std::string summary;       ///< one line: camera side | lidar side
  std::unique_ptr<DatasetSimulator> simulator;  ///< the scene, frames on demand
};

/// The scene of `seed` with `frames` frames at noise factor `noise_k`.
/// Deterministic. Throws Error when no draw of 50 could be placed. The board
/// (board_draw.hpp) comes from streams of its own: a seed's rig, lidar,
/// surroundings and light are the same for both BoardDraw values (the board's
/// distance too, unless its holes differ in size). Beyond Classic, half the
/// solid-state lidars' scenes keep their returns as one cloud accumulated
/// over 1-5 s (SimulationConfig::accumulated_seconds, half of them cropped
/// around the board), from a stream of its own.
L2S_SIM_EXPORT RandomScene make_random_scene(std::uint64_t seed, int frames = 30, double noise_k = 1.0, int threads = 0,
                                             BoardDraw boards = BoardDraw::All);

}  // namespace l2s::sim
