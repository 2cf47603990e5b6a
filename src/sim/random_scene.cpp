// Composes the camera and lidar draws of a seed into one scene. Open space
// (no wall behind the board) is a wall far beyond every working range: the
// lidar's pass-through and the stereo search never reach it.

#include <l2s/sim/random_scene.hpp>

#include <l2s/error.hpp>
#include <l2s/sim/camera_scene_draw.hpp>
#include <l2s/sim/lidar_scene_draw.hpp>

#include "sim/random.hpp"

namespace l2s::sim {
namespace {

constexpr int kMaxDraws = 50;
constexpr double kOpenSpaceWall = 60.0;  // [m] behind the board: beyond any sensor's working range here
constexpr std::uint64_t kSceneStream = 0x5CE9EULL;

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

}  // namespace

RandomScene make_random_scene(std::uint64_t seed, int frames, double noise_k, int threads) {
  RandomScene scene;
  scene.seed = seed;
  std::string last_failure;
  for (int draw = 0; draw < kMaxDraws; ++draw, ++scene.redraws) {
    std::mt19937_64 rng(detail::hash_counters(seed, kSceneStream, static_cast<std::uint64_t>(draw)));
    const CameraSceneDraw camera = draw_camera_scene(rng);
    const LidarSceneDraw lidar = draw_lidar_scene(rng);
    const SimulationConfig config = compose(camera, lidar, seed, frames, noise_k, threads);
    try {
      scene.simulator = std::make_unique<DatasetSimulator>(config);
    } catch (const Error& error) {  // no board pose satisfies both sensors: draw again
      last_failure = error.what();
      continue;
    }
    scene.summary = camera.summary() + " | " + lidar.lidar + (lidar.quirks.any() ? " (quirks)" : "") + ", board " +
                    std::to_string(scene.simulator->board_pose().x).substr(0, 4) + " m";
    return scene;
  }
  throw Error("random scene " + std::to_string(seed) + ": no draw of " + std::to_string(kMaxDraws) +
              " could place the board; last: " + last_failure);
}

}  // namespace l2s::sim
