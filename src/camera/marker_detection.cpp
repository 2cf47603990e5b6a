// Marker detection with OpenCV's aruco module (Garrido-Jurado et al. 2014)
// and the planar pose from their corners: IPPE (Collins & Bartoli 2014) for
// the start, then Levenberg-Marquardt on the reprojection error of all corners.

#include "camera/marker_detection.hpp"

#include "detail/aruco_dictionary.hpp"

#include <opencv2/calib3d.hpp>

#include <algorithm>
#include <cmath>

namespace l2s::detail {

std::vector<MonoBoardDetector::Marker> find_target_markers(const cv::Mat& gray, const MarkerLayout& layout) {
  const cv::Ptr<cv::aruco::Dictionary> dictionary = aruco_dictionary(layout.dictionary);
  const cv::Ptr<cv::aruco::DetectorParameters> params = cv::aruco::DetectorParameters::create();
  // Sub-pixel corners: the pose, and so the hole centres, rest on them.
  params->cornerRefinementMethod = cv::aruco::CORNER_REFINE_SUBPIX;
  params->cornerRefinementWinSize = 4;
  params->cornerRefinementMaxIterations = 50;
  params->cornerRefinementMinAccuracy = 0.005;
  std::vector<std::vector<cv::Point2f>> corners;
  std::vector<int> ids;
  cv::aruco::detectMarkers(gray, dictionary, corners, ids, params);

  std::vector<MonoBoardDetector::Marker> found;
  for (int wanted : layout.ids) {
    if (std::count(ids.begin(), ids.end(), wanted) != 1) continue;
    const std::size_t k = static_cast<std::size_t>(std::find(ids.begin(), ids.end(), wanted) - ids.begin());
    MonoBoardDetector::Marker marker;
    marker.id = wanted;
    for (std::size_t c = 0; c < 4; ++c) marker.corners_px[c] = Eigen::Vector2d(corners[k][c].x, corners[k][c].y);
    found.push_back(marker);
  }
  return found;
}

std::optional<std::array<Eigen::Vector3d, 4>> board_corners(const MonoBoardDetector::Marker& marker,
                                                            const MarkerLayout& layout) {
  const auto found = std::find(layout.ids.begin(), layout.ids.end(), marker.id);
  if (found == layout.ids.end()) return std::nullopt;
  return layout.corners(static_cast<std::size_t>(found - layout.ids.begin()));
}

std::vector<BoardPoseRefiner::PointObservation> corner_observations(const std::vector<MonoBoardDetector::Marker>& markers,
                                                                    const MarkerLayout& layout) {
  std::vector<BoardPoseRefiner::PointObservation> points;
  for (const auto& marker : markers)
    if (const auto corners = board_corners(marker, layout))
      for (std::size_t c = 0; c < 4; ++c) points.push_back({(*corners)[c], marker.corners_px[c]});
  return points;
}

MarkerPose pose_from_markers(const std::vector<MonoBoardDetector::Marker>& markers, const MarkerLayout& layout,
                             const CameraInfo& camera) {
  std::vector<cv::Point3d> board;
  std::vector<cv::Point2d> image;
  for (const auto& marker : markers) {
    const auto corners = board_corners(marker, layout);
    if (!corners) continue;
    for (std::size_t c = 0; c < 4; ++c) {
      board.emplace_back((*corners)[c].x(), (*corners)[c].y(), (*corners)[c].z());
      image.emplace_back(marker.corners_px[c].x(), marker.corners_px[c].y());
    }
  }
  MarkerPose pose;
  if (board.size() < 4) return pose;
  const cv::Matx33d K(camera.fx(), 0.0, camera.cx(), 0.0, camera.fy(), camera.cy(), 0.0, 0.0, 1.0);
  cv::Vec3d rvec, tvec;
  if (!cv::solvePnP(board, image, K, cv::noArray(), rvec, tvec, false, cv::SOLVEPNP_IPPE)) return pose;
  cv::solvePnPRefineLM(board, image, K, cv::noArray(), rvec, tvec);
  std::vector<cv::Point2d> projected;
  cv::projectPoints(board, rvec, tvec, K, cv::noArray(), projected);
  double sum = 0.0;
  for (std::size_t i = 0; i < image.size(); ++i) {
    const cv::Point2d d = projected[i] - image[i];
    sum += d.dot(d);
  }
  cv::Matx33d R;
  cv::Rodrigues(rvec, R);
  Eigen::Matrix3d rotation;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) rotation(r, c) = R(r, c);
  pose.T_camera_board.linear() = rotation;
  pose.T_camera_board.translation() = Eigen::Vector3d(tvec[0], tvec[1], tvec[2]);
  pose.rms_px = std::sqrt(sum / static_cast<double>(image.size()));
  // The board faces the camera: its z axis (out of the front face) points back at it.
  pose.found = pose.T_camera_board.translation().z() > 0.0 &&
               pose.T_camera_board.linear().col(2).dot(pose.T_camera_board.translation()) < 0.0;
  return pose;
}

}  // namespace l2s::detail
