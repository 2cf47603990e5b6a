#pragma once
// The board pose from the target's markers in one image, robust to a
// marker glued off its place: a real board's markers are printed and glued
// by hand, a few millimetres off where target.yaml puts them, and a marker
// that disagrees with the others would tilt the pose they all give.

#include <l2s/camera.hpp>
#include <l2s/mono_board_detector.hpp>

#include <Eigen/Geometry>

#include <vector>

namespace l2s::detail {

/// Board pose from marker corners (in pixels of the ideal camera `camera`:
/// P, no distortion) by PnP over all their corners: IPPE for the start, then
/// Levenberg-Marquardt on the reprojection error.
struct MarkerPose {
  bool found = false;
  Eigen::Isometry3d T_camera_board = Eigen::Isometry3d::Identity();
  double rms_px = 0.0;  ///< [px] corner reprojection rms
};
MarkerPose pose_from_markers(const std::vector<MonoBoardDetector::Marker>& markers, const MarkerLayout& layout,
                             const CameraInfo& camera);

/// Where `marker` lies on the board seen at `T_camera_board`: its corners'
/// rays met with the board's plane, against its place in `layout`.
MonoBoardDetector::MarkerPlacement placement_on_board(const MonoBoardDetector::Marker& marker,
                                                      const MarkerLayout& layout, const CameraInfo& camera,
                                                      const Eigen::Isometry3d& T_camera_board);

/// [px] the corner rms a board's markers must meet under their pose:
/// `params.max_marker_rms_px` (a perfect print), three times the corner
/// noise measured in the image (corner_sigma_px, per coordinate), and the
/// placement tolerance seen by a camera of focal length `fx` at `range_m`,
/// in quadrature.
double marker_rms_limit_px(const MonoBoardDetector::Params& params, double fx, double range_m, double corner_sigma_px);

/// The pose of the markers that agree, from `all` (pose_from_markers of
/// every marker). With four markers or more, the one whose absence lets the
/// others fit best is left out when the others fit within `limit_px` and
/// its corners miss their pose by more than three times their own rms and
/// by more than `min_outlier_px` (the corner noise); it is then placed
/// under their pose, which its own error did not set.
struct RobustMarkerPose {
  MarkerPose pose;                                          ///< of the markers kept
  std::vector<MonoBoardDetector::Marker> kept;              ///< the markers the pose rests on
  /// One per marker, in order: only the one left out is placed (`placed`).
  std::vector<MonoBoardDetector::MarkerPlacement> placements;
};
RobustMarkerPose robust_marker_pose(const std::vector<MonoBoardDetector::Marker>& markers, const MarkerLayout& layout,
                                    const CameraInfo& camera, const MarkerPose& all, double limit_px,
                                    double min_outlier_px);

}  // namespace l2s::detail
