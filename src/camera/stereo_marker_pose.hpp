#pragma once
// The board pose from the target's markers seen in both rectified images:
// one pose whose corners reproject onto the markers of the left and of the
// right image at once, so the baseline holds the board's range, not the
// markers' apparent size in one image alone.

#include <l2s/camera.hpp>
#include <l2s/mono_board_detector.hpp>

#include <Eigen/Geometry>

#include <vector>

namespace l2s::detail {

struct StereoMarkerPose {
  bool found = false;
  Eigen::Isometry3d T_camera_board = Eigen::Isometry3d::Identity();  ///< left rectified frame
  double rms_left_px = 0.0;   ///< [px] corner reprojection rms in the left image (0 without corners there)
  double rms_right_px = 0.0;  ///< [px] ... in the right image
  int left_corners = 0;       ///< corners fitted in the left image
  int right_corners = 0;      ///< ... in the right image
};

/// Fits one board pose to the marker corners of both rectified images
/// (`left`, `right`: markers of `layout`, pixels of `rectified`'s P; either
/// may be empty), starting from the planar pose of the image with more of
/// them and minimising the reprojection error over all corners of both
/// (Gauss-Newton, damped). Not found with fewer than four corners, or when
/// the board would not face the left camera.
StereoMarkerPose stereo_pose_from_markers(const std::vector<MonoBoardDetector::Marker>& left,
                                          const std::vector<MonoBoardDetector::Marker>& right,
                                          const MarkerLayout& layout, const StereoCamera& rectified);

/// The stereo pose of the markers that agree, from `all`
/// (stereo_pose_from_markers of every marker): with four markers or more
/// (by id, in either image), the one whose absence lets the others fit best
/// is left out, from both images, when the others fit within `limit_px`
/// and its corners miss their pose by more than three times their rms and
/// by more than `min_outlier_px`. `left_out_id`: its id, or -1.
StereoMarkerPose robust_stereo_pose_from_markers(const std::vector<MonoBoardDetector::Marker>& left,
                                                 const std::vector<MonoBoardDetector::Marker>& right,
                                                 const MarkerLayout& layout, const StereoCamera& rectified,
                                                 const StereoMarkerPose& all, double limit_px, double min_outlier_px,
                                                 int& left_out_id);

}  // namespace l2s::detail
