#pragma once
// The camera side of scene files and scene records: the `camera:` block
// (image size, field of view, baseline, and a real pair's lenses and mount)
// and the `appearance:` block (looks, light, camera response). Kept apart
// from scene_yaml.cpp so the lidar and the camera side evolve separately.
//
//   camera:
//     width: 1280
//     height: 960
//     horizontal_fov: 1.152          # [rad]
//     baseline: 0.12                 # [m]
//     distortion: plumb_bob          # none | plumb_bob | equidistant: a typical
//                                    # real pair (StereoRig::with_real_lenses);
//                                    # the keys below then refine it
//     raw_images: true               # raw even without distortion
//     right_rotation: [0.002, -0.004, 0.0017]   # [rad] rotation vector
//     right_offset: [0.0, 0.0008, -0.0005]      # [m]
//     left:                          # and right:, each optional
//       focal_scale: 1.0
//       aspect: 1.002
//       principal_offset: [6.0, -4.0]           # [px]
//       distortion: {model: plumb_bob, coefficients: [-0.17, 0.05, 0.0004, -0.0003, 0.0]}
//   appearance:
//     board_texture: wood            # matte | wood | low-contrast
//     background: bricks             # textured | bricks | tiles | plain
//     sky: daylight                  # uniform | daylight
//     brick_length: 0.215            # [m] (tile side for tiles)
//     brick_height: 0.065            # [m]
//     joint_width: 0.01              # [m]
//     to_light: [-1.0, 0.35, 0.6]    # camera body frame, normalised on reading
//     ambient: 0.35
//     shadows: true
//     exposure: 1.0
//     vignetting: 0.0
//     blur_sigma: 0.0                # [px]
//     gamma: 1.0
//     colour: false

#include <l2s/sim/appearance.hpp>
#include <l2s/sim/stereo_rig.hpp>

#include <yaml-cpp/yaml.h>

#include <string>

namespace l2s::sim::detail {

/// Reads the `camera:` map into `rig` (absent keys keep its values). Throws
/// FileError naming `origin` and the key.
void read_camera_block(const YAML::Node& camera, const std::string& origin, StereoRig* rig);
/// Reads the `appearance:` map into `look`; FileError naming the key.
void read_appearance_block(const YAML::Node& appearance, const std::string& origin, Appearance* look);

/// Emits `camera:` and `appearance:` with every key, as the readers take them.
void emit_camera_block(YAML::Emitter& out, const StereoRig& rig);
void emit_appearance_block(YAML::Emitter& out, const Appearance& look);

}  // namespace l2s::sim::detail
