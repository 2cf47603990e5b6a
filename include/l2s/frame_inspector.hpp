#pragma once
// Why was the board (not) found? Runs one frame through the lidar or camera
// branch of the Calibrator, exactly as Calibrator::add does, and keeps what
// every stage produced: the answer to "the board is not detected".

#include <l2s/calibrator.hpp>
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

/// Runs the lidar branch on one sweep and keeps every stage's result.
/// Throws ParamError for invalid params or target (as the Calibrator does).
LidarInspection inspect_lidar(const LidarCloud& sweep, const Target& target,
                              const Calibrator::Params& params);

/// As above for a ring-free lidar: the sweeps (of a static board) are
/// accumulated into one cloud, as the Calibrator does for ring_free_frames sweeps.
LidarInspection inspect_lidar(const std::vector<LidarCloud>& sweeps, const Target& target,
                              const Calibrator::Params& params);

/// Runs the camera branch on one pair (raw images are rectified first, as
/// `cameras.images` says) and keeps every stage's result. Throws ParamError
/// for invalid params or target, or images whose size differs from the cameras.
CameraInspection inspect_camera(const Image& left, const Image& right, const StereoCamera& cameras,
                                const Target& target, const Calibrator::Params& params);

/// A readable account of the branch, one stage per block: counts, the board
/// plane and every rejected candidate with its reason, edge counts, circle
/// candidates in board-plane coordinates, the labelled centres, and the
/// thresholds each stage used (the Params fields to tune). Ends with a newline.
std::string describe(const LidarInspection& inspection, const Calibrator::Params& params);
/// As above; `cameras` (as given to inspect_camera) turn disparities into depths.
std::string describe(const CameraInspection& inspection, const Calibrator::Params& params,
                     const StereoCamera& cameras);

/// Debug picture of a lidar inspection: a top-down view of the filtered sweep
/// (board points, plane candidates) beside a view in the board plane (board
/// points, edge points, where rays through the holes crossed the plane, circle
/// candidates, the four labelled holes and the board outline). BGR.
Image render_lidar_inspection(const LidarInspection& inspection, const Target& target);

/// Debug picture of a camera inspection: the left image (rectified, when the
/// inspection rectified raw images) with the board-plane points tinted, the edge points, the circle candidates and the four labelled
/// holes (stereo circles, and refined rims when the refiner ran). BGR.
Image render_camera_inspection(const Image& left, const CameraInspection& inspection,
                               const StereoCamera& cameras, const Target& target);

/// The disparity map of a camera inspection's whole frame (the coarse pass
/// when the board was located first), colour-coded (near red, far blue;
/// black = no match), at the resolution SGBM ran at. Empty when stereo did not run.
Image render_disparity(const CameraInspection& inspection);

}  // namespace l2s
