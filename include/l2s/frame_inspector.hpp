#pragma once
// Why was the board (not) found? Runs one frame through the lidar or camera
// branch of the Calibrator, exactly as Calibrator::add does, and keeps what
// every stage produced: the answer to "the board is not detected".

#include <l2s/calibrator.hpp>
#include <l2s/export.hpp>
#include <l2s/stereo_rectifier.hpp>

#include <Eigen/Geometry>
#include <optional>
#include <string>

namespace l2s {

/// Every stage of the lidar branch for one sweep. A stage that did not run
/// (an earlier one failed) is empty; `report` names the failing stage.
struct LidarInspection {
  BranchReport report;  ///< what Calibrator::add reports for this sweep
  std::optional<PassThroughFilter::Result> pass_through;  ///< indices into the input sweep
  bool ring_free = false;  ///< no ring structure: hole edges from the board's occupancy, not ring discontinuities
  std::string path;        ///< why this path, in words (lidar_path)
  LidarCloud cloud;  ///< the sweep after pass-through, rings filled (ring-free: none): what the later stages index
  std::optional<PlaneSegmenter::Result> plane;  ///< every candidate; inliers index `cloud`
  std::vector<BoardHypothesis> hypotheses;       ///< board-sized planes tried, in order, and their fate
  /// The stages run on the chosen hypothesis (or, when none was chosen, on the
  /// first one tried: the most board-like plane).
  std::optional<DiscontinuityFilter::Result> discontinuities;  ///< ring lidars; sources index `cloud`
  std::optional<OccupancyEdgeFilter::Result> occupancy;        ///< ring-free clouds
  std::optional<CircleFinder::Result> circles;
  /// The plane candidate those stages ran on (index into plane->candidates), -1 when none.
  int candidate = -1;
};

/// Raw images as the camera branch saw them: rectified, with their cameras.
struct RectifiedView {
  Image left;
  Image right;
  StereoCamera cameras;  ///< the rectified pair
  Eigen::Matrix3d R_rect_camera = Eigen::Matrix3d::Identity();  ///< p_rect = R * p_camera
};

/// Every stage of the camera branch for one stereo pair (see LidarInspection).
struct CameraInspection {
  BranchReport report;  ///< what Calibrator::add reports for this pair (centres in the camera frame of DATASET.md)
  /// Raw images only: the rectified pair every later stage (and every pixel
  /// and point below: the rectified frame) refers to.
  std::optional<RectifiedView> rectified;
  std::optional<StereoBoardLocator::Result> located;  ///< the coarse pass and its regions (locate_board)
  /// Full-resolution matching: the whole frame (locate_board off), or the
  /// region of the hypothesis shown below.
  std::optional<StereoMatcher::Result> stereo;
  std::optional<PassThroughFilter::Result> pass_through;  ///< full frame only: indices into stereo->cloud
  StereoCloud cloud;  ///< full frame only: stereo points after pass-through, what `plane` indexes
  /// Board candidates: of the coarse cloud (located->cloud) or of `cloud`.
  std::optional<PlaneSegmenter::Result> plane;
  std::vector<BoardHypothesis> hypotheses;  ///< board-sized planes tried, in order, and their fate
  /// The stages run on the chosen hypothesis (or, when none was chosen, on the
  /// first one tried). `candidate` indexes plane->candidates, -1 when none.
  int candidate = -1;
  StereoCloud board;  ///< its board-plane points at full resolution
  Plane board_plane;  ///< their plane
  std::optional<EdgeFilter::Result> edges;
  std::optional<CircleFinder::Result> circles;
  std::optional<Eigen::Isometry3d> T_camera_board_initial;  ///< pose from the circles, refiner's start
  std::optional<BoardPoseRefiner::Result> refined;          ///< only when params.refine_camera_pose
};

/// The lidar path a sweep takes in the Calibrator, and why in words:
/// params.lidar_scan when it forces one, else the sweep's returns decide
/// (a usable ring field, or scan lines recovered from its elevations).
struct LidarPath {
  bool ring_free = false;
  std::string reason;
};
L2S_EXPORT LidarPath lidar_path(const LidarCloud& sweep, const Calibrator::Params& params);

/// Runs the lidar branch on one sweep and keeps every stage's result.
/// Throws ParamError for invalid params or target (as the Calibrator does).
L2S_EXPORT LidarInspection inspect_lidar(const LidarCloud& sweep, const Target& target,
                              const Calibrator::Params& params);

/// As above for a ring-free lidar: the sweeps (of a static board) are
/// accumulated into one cloud, as the Calibrator does for ring_free_frames sweeps.
L2S_EXPORT LidarInspection inspect_lidar(const std::vector<LidarCloud>& sweeps, const Target& target,
                                         const Calibrator::Params& params);

/// Runs the camera branch on one pair (raw images are rectified first, as
/// `cameras.images` says) and keeps every stage's result. Throws ParamError
/// for invalid params, target or cameras, InputError naming an image that
/// cannot be used (as Calibrator::add).
L2S_EXPORT CameraInspection inspect_camera(const Image& left, const Image& right, const StereoCamera& cameras,
                                const Target& target, const Calibrator::Params& params);

/// A readable account of the branch, one stage per block: counts, the board
/// plane and every rejected candidate with its reason, edge counts, circle
/// candidates in board-plane coordinates, the labelled centres, and the
/// thresholds each stage used (the Params fields to tune). Ends with a newline.
L2S_EXPORT std::string describe(const LidarInspection& inspection, const Calibrator::Params& params);
/// As above; `cameras` turn the disparity search range into depths.
L2S_EXPORT std::string describe(const CameraInspection& inspection, const Calibrator::Params& params,
                     const StereoCamera& cameras);

// Pictures of an inspection: l2s/viz/inspection_images.hpp (l2scalib::viz).

}  // namespace l2s
