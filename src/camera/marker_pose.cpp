// Marker poses (marker_pose.hpp): the planar pose from all corners (IPPE,
// Collins & Bartoli 2014, then Levenberg-Marquardt), a marker placed on the
// board under a given pose, and the one marker that disagrees with the
// others left out.

#include "camera/marker_pose.hpp"

#include "camera/marker_detection.hpp"

#include <opencv2/calib3d.hpp>

#include <algorithm>
#include <cmath>

namespace l2s::detail {
namespace {

std::vector<MonoBoardDetector::Marker> without(const std::vector<MonoBoardDetector::Marker>& markers, std::size_t k) {
  std::vector<MonoBoardDetector::Marker> rest;
  for (std::size_t i = 0; i < markers.size(); ++i)
    if (i != k) rest.push_back(markers[i]);
  return rest;
}

/// [px] rms of `marker`'s corners against their places projected at T.
double corner_rms(const MonoBoardDetector::Marker& marker, const MarkerLayout& layout, const CameraInfo& camera,
                  const Eigen::Isometry3d& T) {
  const auto corners = board_corners(marker, layout);
  if (!corners) return 0.0;
  double sum = 0.0;
  for (std::size_t c = 0; c < 4; ++c) sum += (camera.project(T * (*corners)[c]) - marker.corners_px[c]).squaredNorm();
  return std::sqrt(sum / 4.0);
}

}  // namespace

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

MonoBoardDetector::MarkerPlacement placement_on_board(const MonoBoardDetector::Marker& marker,
                                                      const MarkerLayout& layout, const CameraInfo& camera,
                                                      const Eigen::Isometry3d& T_camera_board) {
  MonoBoardDetector::MarkerPlacement placement;
  placement.id = marker.id;
  const auto nominal = board_corners(marker, layout);
  if (!nominal) return placement;
  // Each corner's ray, in the board frame, met with the front face z = 0.
  const Eigen::Isometry3d T_board_camera = T_camera_board.inverse();
  const Eigen::Vector3d origin = T_board_camera.translation();
  std::array<Eigen::Vector2d, 4> seen{};
  for (std::size_t c = 0; c < 4; ++c) {
    const Eigen::Vector2d& px = marker.corners_px[c];
    const Eigen::Vector3d ray =
        T_board_camera.linear() * Eigen::Vector3d((px.x() - camera.cx()) / camera.fx(), (px.y() - camera.cy()) / camera.fy(), 1.0);
    if (std::abs(ray.z()) < 1e-12) return placement;
    const double s = -origin.z() / ray.z();
    seen[c] = (origin + s * ray).head<2>();
  }
  Eigen::Vector2d centre_seen = Eigen::Vector2d::Zero(), centre_nominal = Eigen::Vector2d::Zero();
  for (std::size_t c = 0; c < 4; ++c) {
    centre_seen += seen[c] / 4.0;
    centre_nominal += (*nominal)[c].head<2>() / 4.0;
  }
  // The turn in the board plane: the mean angle from each nominal corner's
  // direction (about the centre) to the seen one's.
  double sine = 0.0, cosine = 0.0;
  for (std::size_t c = 0; c < 4; ++c) {
    const Eigen::Vector2d a = (*nominal)[c].head<2>() - centre_nominal, b = seen[c] - centre_seen;
    sine += a.x() * b.y() - a.y() * b.x();
    cosine += a.dot(b);
  }
  placement.offset = centre_seen - centre_nominal;
  placement.rotation_deg = std::atan2(sine, cosine) * 180.0 / M_PI;
  placement.rms_px = corner_rms(marker, layout, camera, T_camera_board);
  placement.placed = true;
  return placement;
}

double marker_rms_limit_px(const MonoBoardDetector::Params& params, double fx, double range_m, double corner_sigma_px) {
  const double placement_px = range_m > 0.0 ? params.marker_placement_tolerance * fx / range_m : 0.0;
  // A corner's 2D error is sqrt(2) times one coordinate's.
  const double noise_px = 3.0 * std::sqrt(2.0) * corner_sigma_px;
  return std::sqrt(params.max_marker_rms_px * params.max_marker_rms_px + noise_px * noise_px +
                   placement_px * placement_px);
}

RobustMarkerPose robust_marker_pose(const std::vector<MonoBoardDetector::Marker>& markers, const MarkerLayout& layout,
                                    const CameraInfo& camera, const MarkerPose& all, double limit_px,
                                    double min_outlier_px) {
  RobustMarkerPose robust{all, markers, {}};
  for (const auto& marker : markers) robust.placements.push_back({marker.id});
  if (!all.found || markers.size() < 4) return robust;
  // The marker whose absence lets the others fit best is the suspect; it is
  // left out only when the others agree and it clearly does not.
  std::size_t worst = markers.size();
  MarkerPose rest;
  for (std::size_t k = 0; k < markers.size(); ++k) {
    const MarkerPose others = pose_from_markers(without(markers, k), layout, camera);
    if (others.found && (worst == markers.size() || others.rms_px < rest.rms_px)) worst = k, rest = others;
  }
  if (worst == markers.size() || rest.rms_px > limit_px) return robust;
  const double outlier_px = std::max(min_outlier_px, 3.0 * rest.rms_px);
  if (corner_rms(markers[worst], layout, camera, rest.T_camera_board) <= outlier_px) return robust;
  robust.placements[worst] = placement_on_board(markers[worst], layout, camera, rest.T_camera_board);
  robust.placements[worst].left_out = true;
  robust.kept = without(markers, worst);
  robust.pose = rest;
  return robust;
}

}  // namespace l2s::detail
