#pragma once
// Scene files: a SimulationConfig in YAML, for custom settings, boards and
// board poses. Every key is optional; absent keys keep the defaults.
//
//   setting: 3                 # Table I index, or a custom pose:
//   sensor_pose: {tx: -0.3, ty: 0.2, tz: -0.2, yaw: 0.3, pitch: -0.1, roll: 0.2}
//   lidar: hdl64               # vlp16 | hdl32 | hdl64 | avia | mid360
//   lidar_quirks: true         # all on, or each of them:
//   # lidar_quirks: {laser_table: true, beam_footprint: true, return_mode: strongest, table_seed: 3}
//   frames: 30
//   noise_factor: 1.0
//   seed: 7
//   target: paper2017          # preset name, or the keys of target.yaml:
//   # target: {board_width: 1.2, board_height: 0.8, board_thickness: 0.02,
//   #          hole_radius: 0.12, hole_spacing_x: 0.3, hole_spacing_y: 0.3}
//   board_pose: {x: 3.0, y: 0.1, z: 0.0, yaw: 0.3, pitch: 0.05, roll: 0.05}
//   camera: {width: 1280, height: 960, horizontal_fov: 0.7505, baseline: 0.12}
//   # camera: also distortion, raw_images, lenses and mount of a real pair;
//   # appearance: board texture, background, light and shadows, camera
//   # response. Every key: src/sim/scene_yaml_camera.hpp.
//   appearance: {board_texture: wood, background: bricks, shadows: true}
//   scene:
//     camera_height: 1.5
//     wall_gap: 3.0
//     wall_half_width: 15.0
//     wall_top: 4.0
//     default_clutter: true
//     clutter:                 # extra boxes, camera body frame
//       - {center: [5.0, -2.5, -1.0], size: [1.0, 1.0, 1.0], yaw: 0.3}
//     board_stand: true        # post and base under the board
//     side_wall_distance: 1.5  # corridor walls at y = +-1.5 m (0 = none)
//     near_clutter: 2          # low boxes between the sensors and the board
//     pillar: true
//   strict_placement: true
//   threads: 0

#include <l2s/export.hpp>
#include <l2s/sim/simulation.hpp>

#include <string>

namespace l2s::sim {

/// Reads a scene file; throws FileError naming the file and key on bad input.
L2S_SIM_EXPORT SimulationConfig load_simulation_config(const std::string& path);

/// The same from YAML text (`origin` names the source in error messages).
L2S_SIM_EXPORT SimulationConfig parse_simulation_config(const std::string& yaml_text,
                                         const std::string& origin = "<scene>");

}  // namespace l2s::sim
