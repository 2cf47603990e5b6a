#pragma once
// The picture users check a calibration with: lidar points projected into the
// left image with the estimated transform, coloured by range. Part of
// l2scalib::viz.

#include <l2s/camera.hpp>
#include <l2s/export.hpp>
#include <l2s/types.hpp>

#include <Eigen/Geometry>

namespace l2s {

struct OverlayParams {
  double min_range = 0.5;  ///< [m] colour scale start (red, near)
  double max_range = 8.0;  ///< [m] colour scale end (blue, far)
  int point_radius = 2;    ///< [px] radius of each drawn point, 0..10
};

/// A BGR copy of `left` with the points of `sweep` (lidar frame) drawn where
/// T_lidar_camera says they project. Points behind the camera are skipped.
L2S_VIZ_EXPORT Image render_overlay(const Image& left, const LidarCloud& sweep, const CameraInfo& camera,
                     const Eigen::Isometry3d& T_lidar_camera, const OverlayParams& params = {});

}  // namespace l2s
