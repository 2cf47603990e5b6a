#pragma once
// The pictures users check a calibration with: lidar points projected into
// the left image with the estimated transform, coloured by range; and the
// calibration check's view, the lidar's depth edges over the image's edges.
// Part of l2scalib::viz.

#include <l2s/camera.hpp>
#include <l2s/export.hpp>
#include <l2s/scene_observer.hpp>
#include <l2s/types.hpp>

#include <Eigen/Geometry>
#include <string>

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

/// What the calibration check compares, as a BGR picture of the (rectified)
/// left image, dimmed: its edges as the check sees them (Canny with the
/// observer's thresholds) in blue; the lidar returns as small dots coloured
/// by range (`params`); the lidar's depth discontinuities projected with
/// T_lidar_camera as larger dots, yellow on the board and magenta off it.
/// With a right transform the yellow and magenta dots sit on blue lines;
/// `caption` (e.g. the verdict) is written at the top left.
L2S_VIZ_EXPORT Image render_edge_overlay(const Image& left, const StereoCamera& cameras, const LidarObservation& lidar,
                          const Eigen::Isometry3d& T_lidar_camera, const SceneObserver& observer = SceneObserver(),
                          const std::string& caption = "", const OverlayParams& params = {});

}  // namespace l2s
