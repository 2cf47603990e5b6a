// The mono camera's board detector (issue 9): ArUco markers -> PnP pose ->
// rim refinement -> hole centres. Raw images: the markers are found in the
// raw image (no resampling before the corner refinement), their corners
// undistorted with K and D into the rectified camera of P, where the pose
// and the rims are fitted; the result is turned back into K's frame.

#include <l2s/mono_board_detector.hpp>

#include <l2s/error.hpp>
#include <l2s/stereo_rectifier.hpp>

#include "camera/cv_image.hpp"
#include "camera/marker_corner_noise.hpp"
#include "camera/marker_detection.hpp"
#include "camera/marker_pose.hpp"
#include "detail/board_frame.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace l2s {
namespace {

using Result = MonoBoardDetector::Result;

Result fail(Result result, const char* stage, const std::string& reason) {
  result.found = false;
  result.failed_stage = stage;
  result.reason = reason;
  return result;
}

std::string ids_text(const std::vector<MonoBoardDetector::Marker>& markers) {
  std::ostringstream text;
  for (std::size_t i = 0; i < markers.size(); ++i) text << (i ? ", " : "") << markers[i].id;
  return text.str();
}

std::string format_px(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f", value);
  return text;
}

std::string format_mm(double metres) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f", metres * 1e3);
  return text;
}

/// "marker 3 lies 4.1 mm off its place in target.yaml (x +4.0 mm, y +0.9 mm, turned +0.2 deg): left out of the pose"
std::string left_out_note(const MonoBoardDetector::MarkerPlacement& placement) {
  char text[200];
  std::snprintf(text, sizeof text,
                "marker %d lies %.1f mm off its place in target.yaml (x %+.1f mm, y %+.1f mm, turned %+.2f deg): "
                "left out of the pose",
                placement.id, placement.offset.norm() * 1e3, placement.offset.x() * 1e3, placement.offset.y() * 1e3,
                placement.rotation_deg);
  return text;
}

double largest_shift(const HoleCenters& a, const HoleCenters& b) {
  double shift = 0.0;
  for (std::size_t h = 0; h < 4; ++h) shift = std::max(shift, (a[h] - b[h]).norm());
  return shift;
}

}  // namespace

void MonoBoardDetector::Params::validate() const {
  if (min_markers < 1) throw ParamError("min_markers", "must be >= 1");
  if (!(max_marker_rms_px > 0.0)) throw ParamError("max_marker_rms_px", "must be > 0");
  if (!(marker_placement_tolerance > 0.0)) throw ParamError("marker_placement_tolerance", "must be > 0");
  if (!(max_rim_shift > 0.0)) throw ParamError("max_rim_shift", "must be > 0");
  if (!(marker_weight >= 0.0) || !std::isfinite(marker_weight)) throw ParamError("marker_weight", "must be >= 0");
  try {
    rims.validate();
  } catch (const ParamError& e) {
    throw ParamError("rims." + e.field(), e.problem());
  }
}

MonoBoardDetector::MonoBoardDetector(CameraInfo camera, ImageKind images, Target target)
    : MonoBoardDetector(std::move(camera), images, std::move(target), Params{}) {}

MonoBoardDetector::MonoBoardDetector(CameraInfo camera, ImageKind images, Target target, Params params)
    : camera_(std::move(camera)), images_(images), target_(std::move(target)), params_(std::move(params)) {
  params_.validate();
  target_.validate();
  if (!target_.markers)
    throw ParamError("target.markers", "a mono camera finds the board by its ArUco markers; the target has none");
  if (images_ == ImageKind::Raw) {
    rectifier_ = std::make_shared<const CameraRectifier>(camera_, "left");
    working_ = rectifier_->rectified();
  } else {
    working_ = camera_;
  }
}

MonoBoardDetector::~MonoBoardDetector() = default;
MonoBoardDetector::MonoBoardDetector(MonoBoardDetector&&) noexcept = default;
MonoBoardDetector& MonoBoardDetector::operator=(MonoBoardDetector&&) noexcept = default;

Result MonoBoardDetector::detect(const Image& image) const {
  detail::check_image(image, camera_, "left");
  const MarkerLayout& layout = *target_.markers;
  Result result;
  result.markers_expected = static_cast<int>(layout.ids.size());
  const cv::Mat gray = detail::gray_mat(image, "left");
  result.markers = detail::find_target_markers(gray, layout);
  const int found = static_cast<int>(result.markers.size());
  if (found < params_.min_markers)
    return fail(result, "markers", "found " + std::to_string(found) + " of the target's " +
                                       std::to_string(result.markers_expected) + " markers (need " +
                                       std::to_string(params_.min_markers) + ")");
  // The pose is fitted in the ideal camera of P: raw corners are undistorted first.
  std::vector<Marker> working = result.markers;
  if (rectifier_)
    for (Marker& marker : working)
      for (Eigen::Vector2d& corner : marker.corners_px) corner = rectifier_->rectify_point(corner);
  // The corners' precision is measured in the image as it was taken (raw
  // pixels differ from rectified ones by little at a marker's scale).
  result.corner_sigma_px =
      detail::marker_corner_sigma(gray, result.markers, MarkerLayout::dictionary_bits(layout.dictionary));
  const detail::MarkerPose all = detail::pose_from_markers(working, layout, working_);
  if (!all.found) return fail(result, "pose", "no board pose facing the camera from markers " + ids_text(working));
  result.marker_rms_limit_px = detail::marker_rms_limit_px(params_, working_.fx(), all.T_camera_board.translation().norm(),
                                                           result.corner_sigma_px);
  const detail::RobustMarkerPose robust = detail::robust_marker_pose(
      working, layout, working_, all, result.marker_rms_limit_px, 3.0 * std::sqrt(2.0) * result.corner_sigma_px);
  const detail::MarkerPose& pose = robust.pose;
  result.placements = robust.placements;
  result.marker_rms_px = pose.rms_px;
  if (pose.rms_px > result.marker_rms_limit_px)
    return fail(result, "pose", "marker corners fit the board badly (rms " + format_px(pose.rms_px) + " px > " +
                                    format_px(result.marker_rms_limit_px) +
                                    " px, the limit for this image's corner noise and a " +
                                    format_mm(params_.marker_placement_tolerance) +
                                    " mm placement tolerance): is target.yaml's marker layout this board's?");
  for (const MarkerPlacement& placement : result.placements)
    if (placement.left_out) result.note = left_out_note(placement);
  Eigen::Isometry3d T_working_board = pose.T_camera_board;
  if (params_.refine_with_rims) {
    const Image rectified = rectifier_ ? rectifier_->rectify(image) : Image{};
    const BoardPoseRefiner::Result rims = BoardPoseRefiner(params_.rims).refine(
        rectifier_ ? rectified : image, working_, target_, T_working_board, detail::corner_observations(robust.kept, layout),
        params_.marker_weight);
    const double shift = largest_shift(detail::hole_centres_at(target_, rims.T_camera_board),
                                       detail::hole_centres_at(target_, T_working_board));
    const std::string separator = result.note.empty() ? "" : "; ";
    if (!rims.converged) {
      result.note += separator + "rim refinement did not converge (" + rims.reason + "); marker pose kept";
    } else if (shift > params_.max_rim_shift) {
      result.note += separator + "rim refinement moved a hole by " + std::to_string(shift) + " m; marker pose kept";
    } else {
      T_working_board = rims.T_camera_board;
      result.rim_refined = true;
      result.rim_rms_px = rims.rms_px;
      // The rims pin the board's pose apart from the markers (their corners
      // weigh as a few rim samples each): each marker is placed again
      // under it, more steadily than under the pose of two or three others.
      // Without the rims only a marker left out is placed (under the pose
      // of the others, which agree): two or three small markers alone pin a
      // far board's tilt too loosely to place one of their own.
      for (std::size_t k = 0; k < working.size(); ++k) {
        const bool left_out = result.placements[k].left_out;
        result.placements[k] = detail::placement_on_board(working[k], layout, working_, T_working_board);
        result.placements[k].left_out = left_out;
      }
    }
  }
  // Raw images: back from the rectified frame (p_rect = R p_camera) into K's.
  const Eigen::Isometry3d T_camera_working(
      rectifier_ ? Eigen::Matrix3d(rectifier_->R_rect_camera().transpose()) : Eigen::Matrix3d::Identity());
  result.T_camera_board_markers = T_camera_working * pose.T_camera_board;
  result.T_camera_board = T_camera_working * T_working_board;
  result.centers = detail::hole_centres_at(target_, result.T_camera_board);
  result.found = true;
  return result;
}

}  // namespace l2s
