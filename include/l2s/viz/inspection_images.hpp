#pragma once
// Debug pictures of a frame inspection (`l2s detect`): what each stage of a
// branch found, drawn over the data it ran on. Part of l2scalib::viz.

#include <l2s/export.hpp>
#include <l2s/frame_inspector.hpp>
#include <l2s/types.hpp>

namespace l2s {

/// Debug picture of a lidar inspection: a top-down view of the filtered sweep
/// (board points, plane candidates) beside a view in the board plane (board
/// points, edge points, where rays through the holes crossed the plane, circle
/// candidates, the four labelled holes and the board outline). BGR.
L2S_VIZ_EXPORT Image render_lidar_inspection(const LidarInspection& inspection, const Target& target);

/// Debug picture of a camera inspection: the left image with the board-plane
/// points tinted, the edge points, the circle candidates and the four labelled
/// holes (stereo circles, and refined rims when the refiner ran). BGR.
L2S_VIZ_EXPORT Image render_camera_inspection(const Image& left, const CameraInspection& inspection,
                               const StereoCamera& cameras, const Target& target);

/// The disparity map of a camera inspection's whole frame (the coarse pass
/// when the board was located first), colour-coded (near red, far blue;
/// black = no match), at the resolution SGBM ran at. Empty when stereo did not run.
L2S_VIZ_EXPORT Image render_disparity(const CameraInspection& inspection);

}  // namespace l2s
