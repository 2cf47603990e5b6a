#pragma once
// The camera side of a lidar-mono calibration (issue 9): one image of the
// board with ArUco markers on its front face (target.yaml `markers:`) to the
// four labelled hole centres in the camera frame, the same observation the
// stereo branch makes of a pair. Markers -> board pose by PnP from all their
// corners -> pose refined with the hole rims in the image (BoardPoseRefiner,
// one view) -> hole centres.

#include <l2s/board_pose_refiner.hpp>
#include <l2s/camera.hpp>
#include <l2s/export.hpp>
#include <l2s/geometry.hpp>
#include <l2s/target.hpp>
#include <l2s/types.hpp>

#include <Eigen/Geometry>
#include <array>
#include <memory>
#include <string>
#include <vector>

namespace l2s {

class CameraRectifier;

/// Thread safety: holds only what it was built with (and the rectification
/// maps of raw images, built once); detect() may run concurrently.
class L2S_EXPORT MonoBoardDetector {
 public:
  struct Params {
    int min_markers = 1;               ///< fewest of the target's markers that give a pose (one gives 4 corners), >= 1
    /// [px] rms the corners of a perfect print may keep under the markers'
    /// pose: the corner detector's bias on blurred, foreshortened markers
    /// (up to about 1.4 px on our randomised renderings), > 0. The limit the
    /// corners must meet adds, in quadrature, three times the corner noise
    /// measured in the image and `marker_placement_tolerance` seen at the
    /// board's range.
    double max_marker_rms_px = 1.5;
    /// [m] how far a marker may lie off its place in target.yaml: printed and
    /// glued by hand, markers sit a few millimetres off, > 0.
    double marker_placement_tolerance = 0.005;
    bool refine_with_rims = true;      ///< refine the marker pose with the hole rims in the image (one fit of rims and marker corners)
    double marker_weight = 5.0;        ///< in that fit, each marker corner coordinate weighs as this many rim samples (0: rims alone), >= 0
    BoardPoseRefiner::Params rims;     ///< the rim refinement (its use_right_image is ignored: one view)
    double max_rim_shift = 0.03;       ///< [m] a rim refinement that moves a hole centre farther than this from the marker pose is not trusted (marker pose kept), > 0

    /// Throws ParamError naming the first invalid field.
    void validate() const;
  };

  /// One marker of the target found in the image.
  struct Marker {
    int id = -1;
    std::array<Eigen::Vector2d, 4> corners_px{};  ///< [px] in the image as given (raw or rectified), ArUco order
  };

  /// Where a marker lies on the board, seen under a pose its own corners
  /// did not set (Result::placements), so its error does not hide in it.
  struct MarkerPlacement {
    int id = -1;
    bool placed = false;            ///< measured (false: no pose that pins the board apart from it)
    Eigen::Vector2d offset = Eigen::Vector2d::Zero();  ///< [m] its centre against target.yaml's, board frame x y
    double rotation_deg = 0.0;      ///< [deg] its turn in the board plane (target.yaml cannot hold one)
    double rms_px = 0.0;            ///< [px] its corners' rms under that pose
    bool left_out = false;          ///< the others agree and it does not: the pose rests on them alone
  };

  struct Result {
    bool found = false;          ///< four hole centres
    std::string failed_stage;    ///< "markers", "pose" or "" on success
    std::string reason;          ///< why not, when !found
    HoleCenters centers{};       ///< [m] front-face hole centres, camera frame (raw: the physical camera's), enum Hole order
    Eigen::Isometry3d T_camera_board = Eigen::Isometry3d::Identity();  ///< board pose in the camera frame
    Eigen::Isometry3d T_camera_board_markers = Eigen::Isometry3d::Identity();  ///< the markers' pose before the rims
    std::vector<Marker> markers;  ///< the target's markers found (others in the dictionary are ignored)
    int markers_expected = 0;     ///< markers the target carries
    double marker_rms_px = 0.0;   ///< [px] corner rms under the markers' PnP pose (rectified pixels), of the markers kept
    double marker_rms_limit_px = 0.0;  ///< [px] the rms the corners had to meet (Params::max_marker_rms_px)
    double corner_sigma_px = 0.0;      ///< [px] corner noise measured on the markers' edges in this image
    /// Each marker found, placed on the board under the rim-refined pose
    /// (the rims pin the board apart from the markers). Without the rims
    /// only a marker left out is placed (under the pose of the others,
    /// which agree); the others are not (`placed` false).
    std::vector<MarkerPlacement> placements;
    bool rim_refined = false;     ///< the centres come from the rim refinement
    double rim_rms_px = 0.0;      ///< [px] rms of the rim fit, when refined
    std::string note;             ///< e.g. why the rim refinement was not kept
  };

  /// `camera`: camera_info of the one camera (for a stereo rig: its left);
  /// `images`: raw (K and D apply, the result is in K's frame) or rectified
  /// (P applies). Throws ParamError for invalid params, a target without
  /// markers, or a camera that cannot be undistorted.
  MonoBoardDetector(CameraInfo camera, ImageKind images, Target target);
  MonoBoardDetector(CameraInfo camera, ImageKind images, Target target, Params params);
  ~MonoBoardDetector();
  MonoBoardDetector(MonoBoardDetector&&) noexcept;
  MonoBoardDetector& operator=(MonoBoardDetector&&) noexcept;

  /// Throws InputError("left image: ...") for an image that is empty, not 1
  /// or 3 channels or not of the camera's size; no board is a status.
  Result detect(const Image& image) const;

  const Params& params() const { return params_; }
  const Target& target() const { return target_; }
  /// The camera the poses are computed with: rectified (P, no distortion).
  const CameraInfo& working_camera() const { return working_; }

 private:
  CameraInfo camera_;
  ImageKind images_;
  Target target_;
  Params params_;
  CameraInfo working_;
  std::shared_ptr<const CameraRectifier> rectifier_;  ///< raw images only
};

}  // namespace l2s
