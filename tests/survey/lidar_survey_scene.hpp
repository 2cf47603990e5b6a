#pragma once
// The scenes both lidar surveys (ring_survey, ring_free_survey) measure on:
// the random scenes' lidar draw with the model forced and the board at a
// chosen distance, and the hole centres it truly has.

#include <l2s/error.hpp>
#include <l2s/geometry.hpp>
#include <l2s/sim/lidar_scene_draw.hpp>
#include <l2s/sim/simulation.hpp>

#include <cstdint>
#include <memory>
#include <random>
#include <string>

namespace l2s::survey {

/// The lidar draw of `seed` with `model` forced and the board min_m..max_m
/// away (the first of 50 draws the simulator can place); null when none.
inline std::unique_ptr<sim::DatasetSimulator> make_lidar_scene(const std::string& model, std::uint64_t seed,
                                                               int frames, double min_m, double max_m) {
  for (int draw = 0; draw < 50; ++draw) {
    std::mt19937_64 rng(seed * 7919 + static_cast<std::uint64_t>(draw));
    sim::LidarSceneDraw lidar = sim::draw_lidar_scene(rng);
    lidar.lidar = model;
    lidar.board_distance = min_m + (max_m - min_m) * static_cast<double>(rng() >> 11) / 9007199254740992.0;
    sim::SimulationConfig config;
    lidar.apply_to(&config);
    config.frames = frames;
    config.seed = seed;
    config.threads = 1;
    try {
      return std::make_unique<sim::DatasetSimulator>(config);
    } catch (const Error&) {
    }
  }
  return nullptr;
}

/// The board's hole centres in the lidar frame (front face, target numbering).
inline HoleCenters lidar_truth(const sim::DatasetSimulator& simulator) {
  const Eigen::Isometry3d T_lidar_board =
      simulator.config().setting.T_cambody_lidar().inverse() * simulator.board_pose().T_cambody_board();
  const auto holes = simulator.config().target.hole_centers();
  HoleCenters out;
  for (int h = 0; h < 4; ++h) out[h] = T_lidar_board * Eigen::Vector3d(holes[h].x(), holes[h].y(), 0.0);
  return out;
}

}  // namespace l2s::survey
