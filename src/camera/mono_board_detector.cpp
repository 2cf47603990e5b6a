// The mono camera's board detector (issue 9): ArUco markers -> PnP pose ->
// rim refinement -> hole centres. Raw images: the markers are found in the
// raw image (no resampling before the corner refinement), their corners
// undistorted with K and D into the rectified camera of P, where the pose
// and the rims are fitted; the result is turned back into K's frame.

#include <l2s/mono_board_detector.hpp>

#include <l2s/error.hpp>
#include <l2s/stereo_rectifier.hpp>

#include "camera/cv_image.hpp"
#include "camera/marker_detection.hpp"
#include "detail/board_frame.hpp"

#include <algorithm>
#include <cmath>
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

double largest_shift(const HoleCenters& a, const HoleCenters& b) {
  double shift = 0.0;
  for (std::size_t h = 0; h < 4; ++h) shift = std::max(shift, (a[h] - b[h]).norm());
  return shift;
}

}  // namespace

void MonoBoardDetector::Params::validate() const {
  if (min_markers < 1) throw ParamError("min_markers", "must be >= 1");
  if (!(max_marker_rms_px > 0.0)) throw ParamError("max_marker_rms_px", "must be > 0");
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
  result.markers = detail::find_target_markers(detail::gray_mat(image, "left"), layout);
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
  const detail::MarkerPose pose = detail::pose_from_markers(working, layout, working_);
  result.marker_rms_px = pose.rms_px;
  if (!pose.found) return fail(result, "pose", "no board pose facing the camera from markers " + ids_text(working));
  if (pose.rms_px > params_.max_marker_rms_px)
    return fail(result, "pose", "marker corners fit the board badly (rms " + std::to_string(pose.rms_px) +
                                    " px > " + std::to_string(params_.max_marker_rms_px) + ")");
  Eigen::Isometry3d T_working_board = pose.T_camera_board;
  if (params_.refine_with_rims) {
    const Image rectified = rectifier_ ? rectifier_->rectify(image) : Image{};
    const BoardPoseRefiner::Result rims = BoardPoseRefiner(params_.rims).refine(
        rectifier_ ? rectified : image, working_, target_, T_working_board, detail::corner_observations(working, layout),
        params_.marker_weight);
    const double shift = largest_shift(detail::hole_centres_at(target_, rims.T_camera_board),
                                       detail::hole_centres_at(target_, T_working_board));
    if (!rims.converged) {
      result.note = "rim refinement did not converge (" + rims.reason + "); marker pose kept";
    } else if (shift > params_.max_rim_shift) {
      result.note = "rim refinement moved a hole by " + std::to_string(shift) + " m; marker pose kept";
    } else {
      T_working_board = rims.T_camera_board;
      result.rim_refined = true;
      result.rim_rms_px = rims.rms_px;
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
