#pragma once
// The two per-frame branches of the pipeline, each from raw sensor data to four
// labelled hole centres in its own frame (paper Sec. III-A to III-C).
//
// Each branch keeps its stages' results in an inspection struct: the caller's
// when `trace` is given (frame_inspector.hpp), otherwise a local one, so the
// traced and untraced runs are the same code and neither copies stage data.

#include <l2s/calibrator.hpp>
#include <l2s/frame_inspector.hpp>

namespace l2s::detail {

/// Lidar: rings, pass-through, board plane, depth discontinuities, circles.
/// `trace`, when given, receives every stage's result (its report is not set).
BranchReport run_lidar_branch(const LidarCloud& sweep, const Target& target,
                              const Calibrator::Params& params, LidarInspection* trace = nullptr);

/// Camera: SGM stereo, pass-through, board plane, Sobel edges, circles, and
/// (default preset) the board pose fitted to the hole rims in both images.
BranchReport run_camera_branch(const Image& left, const Image& right, const StereoCamera& cameras,
                               const Target& target, const Calibrator::Params& params,
                               CameraInspection* trace = nullptr);

}  // namespace l2s::detail
