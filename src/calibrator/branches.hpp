#pragma once
// The two per-frame branches of the pipeline, each from raw sensor data to four
// labelled hole centres in its own frame (paper Sec. III-A to III-C).
//
// Each branch keeps its stages' results in an inspection struct: the caller's
// when `trace` is given (frame_inspector.hpp), otherwise a local one, so the
// traced and untraced runs are the same code and neither copies stage data.

#include <l2s/calibrator.hpp>
#include <l2s/frame_inspector.hpp>
#include <l2s/stereo_rectifier.hpp>

#include <memory>
#include <string>

namespace l2s::detail {

/// Lidar: rings, pass-through, board plane, hole edges, circles. Hole edges
/// come from depth discontinuities along the rings, or, for a ring-free cloud
/// (a non-repetitive scan, accumulated), from the board's occupancy.
/// `trace`, when given, receives every stage's result (its report is not set).
BranchReport run_lidar_branch(const LidarCloud& sweep, const Target& target,
                              const Calibrator::Params& params, LidarInspection* trace = nullptr);

/// The lidar branch on a window of ring-free sweeps (accumulate_ring_free):
/// ring-free as its sweeps were found to be, not classified again (a window
/// after pass-through can show chance lines that one sweep does not).
BranchReport run_ring_free_branch(const LidarCloud& window, const Target& target,
                                  const Calibrator::Params& params, LidarInspection* trace = nullptr);

/// The path of a sweep (l2s::lidar_path): ring-free or not, whether its ring
/// field is used (else rings are recovered from the returns), and why.
struct SweepPath {
  bool ring_free = false;
  bool use_field = false;
  std::string reason;
};
SweepPath choose_path(const LidarCloud& sweep, const Calibrator::Params& params);

/// Does this sweep go the ring-free way (choose_path)? Such sweeps are
/// accumulated, then detected as one ring-free cloud. Bad input (fields of
/// the wrong length) goes the ring way, whose report names the fault.
bool is_ring_free(const LidarCloud& sweep, const Calibrator::Params& params);

/// The sweeps of a static board as one ring-free cloud: each sweep's points
/// inside the lidar pass-through (ring and intensity dropped).
LidarCloud accumulate_ring_free(const std::vector<const LidarCloud*>& sweeps, const Calibrator::Params& params);

/// The cameras as the camera branch works with them: rectified. For raw
/// images, the rectifier (its maps are built once) and the rectified pair.
struct CameraSetup {
  StereoCamera cameras;                         ///< rectified: what the stages use
  std::shared_ptr<const StereoRectifier> rectifier;  ///< set for raw images

  /// Throws ParamError for cameras a rectifier cannot be built for.
  explicit CameraSetup(const StereoCamera& given);
};

/// Camera: (raw images: rectification), SGM stereo, board plane, Sobel edges,
/// circles, and (default preset) the board pose fitted to the hole rims in
/// both images. The centres come in the camera frame of DATASET.md: for raw
/// images the physical left camera's, not the rectified frame.
BranchReport run_camera_branch(const Image& left, const Image& right, const CameraSetup& setup,
                               const Target& target, const Calibrator::Params& params,
                               CameraInspection* trace = nullptr);

/// Mono camera: the board by its markers (MonoBoardDetector), as a branch
/// report: the same four centres in the camera frame as the stereo branch's.
BranchReport run_mono_branch(const Image& left, const MonoBoardDetector& detector);

}  // namespace l2s::detail
