// Composes the camera and lidar draws of a seed into one scene. Open space
// (no wall behind the board) is a wall far beyond every working range: the
// lidar's pass-through and the stereo search never reach it.

#include <l2s/sim/random_scene.hpp>

#include <l2s/error.hpp>
#include <l2s/sim/board_draw.hpp>
#include <l2s/sim/camera_scene_draw.hpp>
#include <l2s/sim/lidar_model.hpp>
#include <l2s/sim/lidar_scene_draw.hpp>
#include <l2s/sim/mounting_draw.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "sim/draw_random.hpp"
#include "sim/random.hpp"

namespace l2s::sim {
namespace {

constexpr int kMaxDraws = 50;
constexpr double kOpenSpaceWall = 60.0;  // [m] behind the board: beyond any sensor's working range here
constexpr std::uint64_t kSceneStream = 0x5CE9EULL;
constexpr std::uint64_t kFaceStream = 0xFACE5ULL;
constexpr std::uint64_t kMarkerStream = 0xA1C0ULL;
constexpr std::uint64_t kBoardStream = 0xB0A4DULL;
constexpr std::uint64_t kRigStream = 0x5E7E0ULL;
constexpr std::uint64_t kMountStream = 0x0A7C4ULL;
constexpr std::uint64_t kFormStream = 0xACC0ULL;
constexpr double kNearest = 1.5;             // [m] the lidar draw's nearest board
constexpr double kMinHolePixels = 10.0;      // [px] hole radius in the image at the farthest board
constexpr double kMinBoardDisparity = 10.0;  // [px] disparity at the farthest board

/// [m] how far the board may stand for this rig to resolve it: a hole at
/// least kMinHolePixels in radius (its rim is the camera's evidence) and a
/// disparity of kMinBoardDisparity (depth noise grows as d^2 / (fx B)). A user
/// places the board for the rig at hand; a draw that this rig cannot resolve
/// tests the draw, not the method.
double camera_reach(const StereoRig& rig, double hole_radius) {
  return std::min(rig.fx() * hole_radius / kMinHolePixels, rig.fx() * rig.baseline / kMinBoardDisparity);
}

/// The lidar draw's board distance, uniform over [kNearest, lidar reach], mapped
/// onto [kNearest, min(lidar reach, camera reach)] so it stays uniform.
double shared_distance(const LidarSceneDraw& lidar, double camera_limit) {
  const double lidar_limit = lidar.reach;
  if (camera_limit >= lidar_limit) return lidar.board_distance;
  const double share = (lidar.board_distance - kNearest) / (lidar_limit - kNearest);
  return kNearest + share * (camera_limit - kNearest);
}

SimulationConfig compose(const CameraSceneDraw& camera, const LidarSceneDraw& lidar, std::uint64_t seed, int frames,
                         double noise_k, int threads) {
  SimulationConfig config;
  lidar.apply_to(&config);
  config.rig = camera.rig;
  config.appearance = camera.appearance;
  config.layout.wall_gap = camera.open_space ? kOpenSpaceWall : camera.wall_gap;
  config.frames = frames;
  config.noise_factor = noise_k;
  config.seed = seed;
  config.threads = threads;
  return config;
}

/// How a solid-state lidar's returns are kept: half the time as one cloud
/// accumulated over 1-5 s of the static board (DATASET.md `lidar:
/// accumulated`, as users of such sensors record it), and of those half
/// cropped to 0.2-0.6 m around the board, as a user cuts it out by hand.
void draw_lidar_form(std::mt19937_64& rng, SimulationConfig* config) {
  if (LidarModel::by_name(config->lidar).has_rings() || !detail::chance(rng, 0.5)) return;
  config->accumulated_seconds = std::round(detail::uniform(rng, 1.0, 5.0) * 10.0) / 10.0;  // whole sweeps at 10 Hz
  if (detail::chance(rng, 0.5)) config->accumulated_crop = detail::uniform(rng, 0.2, 0.6);
}

/// ", accumulated 2.3 s" (", cropped" when cut out around the board), or "".
std::string lidar_form_summary(const SimulationConfig& config) {
  if (!(config.accumulated_seconds > 0.0)) return "";
  char line[64];
  std::snprintf(line, sizeof line, ", accumulated %.1f s%s", config.accumulated_seconds,
                config.accumulated_crop > 0.0 ? " cropped" : "");
  return line;
}

/// ", board 1.20x0.90 r0.10 on 0.60x0.45" when not the default board, and
/// ", markers DICT_..." when it carries markers.
std::string board_summary(const Target& board) {
  std::string text;
  const Target standard;
  if (board.board_width != standard.board_width || board.board_height != standard.board_height ||
      board.hole_radius != standard.hole_radius || board.hole_spacing_x != standard.hole_spacing_x ||
      board.hole_spacing_y != standard.hole_spacing_y) {
    char line[96];
    std::snprintf(line, sizeof line, ", board %.2fx%.2f r%.2f on %.2fx%.2f", board.board_width, board.board_height,
                  board.hole_radius, board.hole_spacing_x, board.hole_spacing_y);
    text += line;
  }
  if (board.markers) text += ", markers " + board.markers->dictionary;
  return text;
}

}  // namespace

RandomScene make_random_scene(std::uint64_t seed, int frames, double noise_k, int threads, BoardDraw boards) {
  RandomScene scene;
  scene.seed = seed;
  std::string last_failure;
  for (int draw = 0; draw < kMaxDraws; ++draw, ++scene.redraws) {
    std::mt19937_64 rng(detail::hash_counters(seed, kSceneStream, static_cast<std::uint64_t>(draw)));
    CameraSceneDraw camera = draw_camera_scene(rng);
    const bool any_board = boards != BoardDraw::Classic;
    if (any_board) {
      std::mt19937_64 face_rng(detail::hash_counters(seed, kFaceStream, static_cast<std::uint64_t>(draw)));
      draw_board_face(face_rng, &camera.appearance);
    }
    LidarSceneDraw lidar = draw_lidar_scene(rng);
    if (any_board) {
      std::mt19937_64 rig_rng(detail::hash_counters(seed, kRigStream, static_cast<std::uint64_t>(draw)));
      draw_special_rig(rig_rng, &camera.rig);
    }
    if (boards == BoardDraw::All) {
      std::mt19937_64 mount_rng(detail::hash_counters(seed, kMountStream, static_cast<std::uint64_t>(draw)));
      draw_mounting(mount_rng, &camera.rig, &lidar.lidar_pose);
    }
    Target board;
    if (any_board) {
      std::mt19937_64 board_rng(detail::hash_counters(seed, kBoardStream, static_cast<std::uint64_t>(draw)));
      draw_board_geometry(board_rng, &board);
      std::mt19937_64 marker_rng(detail::hash_counters(seed, kMarkerStream, static_cast<std::uint64_t>(draw)));
      draw_board_markers(marker_rng, &board, boards == BoardDraw::Marked ? 1.0 : 1.0 / 3.0);
    }
    const double camera_limit = camera_reach(camera.rig, board.hole_radius);
    if (camera_limit < kNearest) {  // this rig sees no board at a distance the lidar draw allows
      last_failure = "the rig resolves the holes only up to " + std::to_string(camera_limit) + " m";
      continue;
    }
    lidar.board_distance = shared_distance(lidar, camera_limit);
    SimulationConfig config = compose(camera, lidar, seed, frames, noise_k, threads);
    config.target = board;
    if (any_board) {
      std::mt19937_64 form_rng(detail::hash_counters(seed, kFormStream, static_cast<std::uint64_t>(draw)));
      draw_lidar_form(form_rng, &config);
    }
    try {
      scene.simulator = std::make_unique<DatasetSimulator>(config);
    } catch (const Error& error) {  // no board pose satisfies both sensors: draw again
      last_failure = error.what();
      continue;
    }
    const bool upside_down = std::cos(lidar.lidar_pose.roll) < 0.0;
    scene.summary = camera.summary() + board_summary(board) + " | " + lidar.lidar +
                    (upside_down ? " upside down" : "") + (lidar.quirks.any() ? " (quirks)" : "") + lidar_form_summary(config) + ", board " +
                    std::to_string(scene.simulator->board_pose().x).substr(0, 4) + " m";
    return scene;
  }
  throw Error("random scene " + std::to_string(seed) + ": no draw of " + std::to_string(kMaxDraws) +
              " could place the board; last: " + last_failure);
}

}  // namespace l2s::sim
