#pragma once
// The registration step of Calibrator::result(): frames -> board poses ->
// centres clustered per pose and sensor -> one joint fit (private).

#include <l2s/calibrator.hpp>
#include <l2s/target.hpp>

#include <array>
#include <optional>
#include <string>

namespace l2s::detail {

/// How a pose's detections err beyond the joint fit's pose bias
/// (JointRegistrar::Params: the error one pose's detections share where a
/// ring lidar's share dominates, VLP-16 beside a stereo camera refined on its
/// rims). The source camera's with range: its range comes from an image
/// distance of base / range [px] (a disparity, base = fx B; for a mono camera
/// the marker span, base = fx times its width), measured to bias_px in every
/// frame of a pose alike; base 0: not modelled. Any sensor's further share as
/// a rigid motion per axis (isotropic, so either frame): a second lidar's
/// (lidar to lidar: two lidars bring two shares), a ring-free lidar's larger one.
struct SourceRange {
  double base = 0.0;              ///< [m px]
  double bias_px = 0.0;           ///< [px] Calibrator::Params::camera_range_bias_px
  double extra_translation = 0.0; ///< [m] per axis
  double extra_rotation = 0.0;    ///< [rad] per axis
};

/// A ring-free lidar's detection of a pose shares this many times more error
/// across its centres than a ring lidar's (the joint fit's pose bias), added
/// in quadrature: sqrt(1 + 2.3^2) = 2.5 times in all. On 100 random scenes
/// (default preset, 30 frames) the result's lidar centres were off by 1.74
/// mm (Avia) and 2.71 mm (Mid-360) rms in the median, 3.0 and 3.3 mm at the
/// 90th percentile, against 1.03-1.08 mm (1.4-1.6 mm) for the ring lidars;
/// the 95 % bounds missed a DoF in 6 of the 14 Mid-360 runs. With this share
/// they held all six DoFs in 34 of the 37 ring-free runs instead of 27.
constexpr double kRingFreePoseShare = 2.3;

/// Stream 0's evidence beyond its centres, per frame (a lidar's).
struct TargetStreamEvidence {
  std::vector<std::optional<Plane>> planes;         ///< its board plane, when known
  std::vector<std::vector<RimCrossing>> crossings;  ///< ring lidars: where its rings crossed the hole rims
  std::optional<Target> target;                     ///< the board, for fitting a pose's crossings
};

/// Groups `frames` into board poses, clusters each pose's centres per sensor
/// and registers all usable poses jointly. `late_lidar`: a lidar detection not
/// in any frame report yet (a ring-free window detected as it stands), counted
/// with the last frame. Fills result.poses, moving_frames, the centroids,
/// registration, joint and T_lidar_camera; false with result.reason set when
/// no transform is found. With params.fit_lidar_rim_crossings each pose's
/// lidar centres are the `target` pattern fitted to its rim crossings.
bool register_poses(const std::vector<FrameReport>& frames, const std::optional<HoleCenters>& late_lidar,
                    const Target& target, const Calibrator::Params& params, const SourceRange& camera_range,
                    Calibrator::Result& result);

/// What the two streams are called in reasons ("lidar", "camera").
using StreamNames = std::array<std::string, 2>;

/// register_poses() on any two observation streams (frame f's centres of
/// stream s in streams[f][s]; stream 0 is the target of the fit, stream 1 the
/// source), e.g. two lidars. The result's lidar_* fields hold stream 0, its
/// camera_* fields stream 1, T_lidar_camera the fitted T_stream0_stream1.
/// `lidar`: stream 0's board plane per frame, when known; with them (and
/// params.refine_with_board_planes) the fit is refined with each used pose's
/// planes, stream 1's through its centres; its rim crossings, when known
/// (and params.fit_lidar_rim_crossings), give each pose's stream 0 centres.
/// `coarse_source`: frames whose stream 1 centres are a fallback (the camera's stereo circle fit when
/// its rim refinement failed); a pose with enough other frames leaves them out.
bool register_pose_streams(const std::vector<FrameCenters>& streams, const StreamNames& names,
                           const Calibrator::Params& params, Calibrator::Result& result,
                           const TargetStreamEvidence& lidar = {},
                           const std::vector<bool>& coarse_source = {}, const SourceRange& source_range = {});

/// Whether the board-plane refinement may trust the lidar centres of the used
/// poses (those with a lidar plane) tightly: each pose's are the pattern
/// fitted to its rim crossings, with holes as large as the target's (within
/// 1 %). A beam footprint makes the holes look smaller, and where a ring
/// seems to leave the board then depends on the echo: such centres were
/// 1-1.7 mm off, as biased as clustered ones.
bool lidar_centres_sharp(const std::vector<PoseReport>& poses);

/// The joint fit of result.poses again with every pose's camera centres
/// relabelled by `permutation` (the labels the scene prefers); updates the
/// centroids, registration, joint and T. False when the fit fails.
bool refit_relabelled(Calibrator::Result& result, const HolePermutation& permutation,
                      const Calibrator::Params& params, const SourceRange& source_range);

}  // namespace l2s::detail
