#pragma once
// The two per-frame branches of the pipeline, each from raw sensor data to four
// labelled hole centres in its own frame (paper Sec. III-A to III-C).

#include <l2s/calibrator.hpp>

namespace l2s::detail {

/// Lidar: rings, pass-through, board plane, depth discontinuities, circles.
BranchReport run_lidar_branch(const LidarCloud& sweep, const Target& target,
                              const Calibrator::Params& params);

/// Camera: SGM stereo, pass-through, board plane, Sobel edges, circles, and
/// (default preset) the board pose fitted to the hole rims in both images.
BranchReport run_camera_branch(const Image& left, const Image& right, const StereoCamera& cameras,
                               const Target& target, const Calibrator::Params& params);

}  // namespace l2s::detail
