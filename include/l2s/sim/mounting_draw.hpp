#pragma once
// How the sensors of a randomised scene are mounted, and which rig users
// bring besides the common ones, drawn apart from the rest of the scene
// (each from a generator of its own, as the boards are: board_draw.hpp), so
// that a seed's scene keeps its look, lidar and geometry.

#include <l2s/export.hpp>
#include <l2s/sim/settings.hpp>
#include <l2s/sim/stereo_rig.hpp>

#include <random>

namespace l2s::sim {

/// Draws the rig's roll about its optical axis and the lidar's attitude over
/// what the scene drew: in about a third of the draws the rig is rolled
/// beyond 20 deg (on its side at +-90 deg, upside down at 180 deg, or
/// anywhere else in 20-340 deg, each a quarter of those), otherwise level;
/// in about 15 % the lidar hangs upside down (its roll turned by 180 deg).
L2S_SIM_EXPORT void draw_mounting(std::mt19937_64& mounts, StereoRig* rig, SensorSetting* lidar);

/// In about a quarter of the draws replaces `rig` by one of the rigs users
/// bring besides the common industrial pairs: a depth-camera-like pair
/// (848x480, 87 deg, 5 cm baseline, rectified), a 5 MP wide raw pair
/// (2448x2048, 100 deg, equidistant lenses, the right camera toed in by
/// 1-3 deg: rectified by camera_info R and P), or a narrow long-baseline pair
/// (40 deg, 0.4 m, raw plumb_bob). Otherwise `rig` stays as drawn. Keeps
/// `rig`'s roll.
L2S_SIM_EXPORT void draw_special_rig(std::mt19937_64& rigs, StereoRig* rig);

}  // namespace l2s::sim
