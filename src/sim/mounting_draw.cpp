// Mountings are those users report: pairs on their side or upside down to
// fit a bracket, lidars hung under a roof rack; rigs from depth-camera pairs
// to 5 MP wide raw pairs with toed-in cameras.

#include <l2s/sim/mounting_draw.hpp>

#include <l2s/error.hpp>

#include "sim/draw_random.hpp"

#include <array>
#include <cmath>

namespace l2s::sim {

using detail::chance;
using detail::pick;
using detail::uniform;

namespace {

constexpr double kDeg = 3.141592653589793 / 180.0;

/// An ideal rectified pair of this size, view and baseline.
StereoRig pair(int width, int height, double hfov_deg, double baseline) {
  StereoRig rig;
  rig.width = width;
  rig.height = height;
  rig.horizontal_fov = hfov_deg * kDeg;
  rig.baseline = baseline;
  return rig;
}

/// A 5 MP wide pair with fisheye-style lenses, its right camera toed in
/// (turned towards the left one about the vertical axis) as wide pairs are
/// mounted to share more of the view: only camera_info's R and P make its
/// rows line up.
StereoRig wide_raw_pair(std::mt19937_64& rigs) {
  StereoRig rig = pair(2448, 2048, 100.0, uniform(rigs, 0.12, 0.3)).with_real_lenses(DistortionModel::Equidistant);
  rig.right_rotation.y() -= uniform(rigs, 1.0, 3.0) * kDeg;  // about the optical y axis, towards the left camera
  return rig;
}

}  // namespace

void draw_mounting(std::mt19937_64& mounts, StereoRig* rig, SensorSetting* lidar) {
  if (chance(mounts, 1.0 / 3.0)) {
    constexpr std::array<double, 3> kRolls{90.0, -90.0, 180.0};
    const std::size_t which = pick(mounts, std::array<double, 4>{1, 1, 1, 1});
    rig->roll = (which < kRolls.size() ? kRolls[which] : uniform(mounts, 20.0, 340.0)) * kDeg;
  }
  if (chance(mounts, 0.15)) lidar->roll += 180.0 * kDeg;
}

void draw_special_rig(std::mt19937_64& rigs, StereoRig* rig) {
  if (!chance(rigs, 0.25)) return;
  const double roll = rig->roll;
  switch (pick(rigs, std::array<double, 3>{1, 1, 1})) {
    case 0:  // a depth-camera-like pair, rectified on board
      *rig = pair(848, 480, 87.0, 0.05);
      break;
    case 1:
      *rig = wide_raw_pair(rigs);
      break;
    default:  // a narrow long-baseline pair for far boards
      *rig = pair(1920, 1200, 40.0, 0.4).with_real_lenses(DistortionModel::PlumbBob);
      break;
  }
  rig->roll = roll;
  rig->validate();
}

}  // namespace l2s::sim
