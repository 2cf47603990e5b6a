#pragma once
// A random draw of the lidar side of a scene, for the randomised `scenes`
// experiment: the lidar model and its quirks (one drawn unit), its mounting
// relative to the camera, the scene elements of a real recording and where
// the board stands. The camera side (rig, appearance) is drawn separately;
// both write into one SimulationConfig:
//
//   std::mt19937_64 rng(seed);
//   SimulationConfig config;
//   draw_lidar_scene(rng).apply_to(&config);   // lidar, pose, quirks, layout, placement search
//   ... the camera draw sets config.rig and the appearance ...
//   DatasetSimulator simulator(config);        // places the board; throws when no pose fits: redraw
//
// The draw uses only the generator's raw 64-bit output (no std::
// distributions), so one seed gives the same scene on every platform.

#include <l2s/sim/lidar_quirks.hpp>
#include <l2s/sim/placement.hpp>
#include <l2s/sim/scene.hpp>
#include <l2s/sim/settings.hpp>
#include <l2s/sim/simulation.hpp>

#include <random>
#include <string>

namespace l2s::sim {

/// The lidar side of one scene.
struct LidarSceneDraw {
  std::string lidar = "vlp16";  ///< vlp16 | hdl32 | hdl64 | mid360 | avia, equally likely
  LidarQuirks quirks;           ///< all on; a drawn table seed; strongest 70 %, last 20 %, first 10 %
  SensorSetting lidar_pose;     ///< in the camera body frame: within 1 m, yaw +-0.7, pitch and roll +-0.3 rad
  SceneLayout layout;           ///< stand 70 %, side walls 50 % (1-3 m), 0-3 near boxes, pillar 30 %
  double board_distance = 3.0;  ///< [m] 1.5 m up to the model's reach: VLP-16 3.5, HDL-32E 4.5, Mid-360 5, others 6
  double reach = 6.0;           ///< [m] that reach (the farthest board_distance of this model)
  double board_yaw = 0.3;       ///< [rad] 0.1..0.5 either way (never square to the sensors)
  double board_pitch = 0.0;     ///< [rad] +-0.1
  double board_roll = 0.0;      ///< [rad] +-0.1

  /// The placement search for this draw: the drawn distance and attitude,
  /// the lateral offsets and heights of the default search.
  PlacementSearch placement_search() const;

  /// Writes the lidar side into `config`: lidar, lidar_quirks, the lidar
  /// pose as a custom setting (setting_index 0), layout, placement_search
  /// (the board pose is left to the simulator). Camera and appearance fields
  /// are left alone.
  void apply_to(SimulationConfig* config) const;
};

/// Draws the lidar side of one scene from `rng` (advances it).
LidarSceneDraw draw_lidar_scene(std::mt19937_64& rng);

}  // namespace l2s::sim
