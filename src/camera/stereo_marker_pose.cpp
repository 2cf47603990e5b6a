// One pose for both images: each marker corner X (board frame) lands at
// P_left [T X; 1] in the left rectified image and at P_right [T X; 1] in the
// right one, whose P carries the baseline (-fx B in its last column). The
// start is the image's own planar pose (marker_detection.hpp), moved into
// the left frame for the right image; Gauss-Newton then weighs every corner
// of both images alike.

#include "camera/stereo_marker_pose.hpp"

#include "camera/marker_detection.hpp"
#include "camera/marker_pose.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <set>

namespace l2s::detail {
namespace {

/// A marker corner: where it is on the board and where it was seen.
struct Corner {
  Eigen::Vector3d X_board;
  Eigen::Vector2d pixel;
  int image = 0;  ///< 0 left, 1 right
};

std::vector<Corner> corners_of(const std::vector<MonoBoardDetector::Marker>& markers, const MarkerLayout& layout,
                               int image) {
  std::vector<Corner> out;
  for (const auto& marker : markers)
    if (const auto board = board_corners(marker, layout))
      for (std::size_t c = 0; c < 4; ++c) out.push_back({(*board)[c], marker.corners_px[c], image});
  return out;
}

Eigen::Vector2d project(const Eigen::Matrix<double, 3, 4>& P, const Eigen::Vector3d& X) {
  const Eigen::Vector3d p = P.leftCols<3>() * X + P.col(3);
  return p.head<2>() / p.z();
}

/// The pose moved by a small twist: a rotation vector and a translation,
/// applied in the camera frame.
Eigen::Isometry3d moved(const Eigen::Isometry3d& T, const Eigen::Matrix<double, 6, 1>& twist) {
  Eigen::Isometry3d step = Eigen::Isometry3d::Identity();
  const double angle = twist.head<3>().norm();
  if (angle > 0.0) step.linear() = Eigen::AngleAxisd(angle, twist.head<3>() / angle).toRotationMatrix();
  step.translation() = twist.tail<3>();
  return step * T;
}

Eigen::VectorXd residuals(const std::vector<Corner>& corners, const std::array<Eigen::Matrix<double, 3, 4>, 2>& P,
                          const Eigen::Isometry3d& T) {
  Eigen::VectorXd r(2 * static_cast<Eigen::Index>(corners.size()));
  for (std::size_t i = 0; i < corners.size(); ++i)
    r.segment<2>(2 * static_cast<Eigen::Index>(i)) =
        project(P[static_cast<std::size_t>(corners[i].image)], T * corners[i].X_board) - corners[i].pixel;
  return r;
}

double rms_of(const std::vector<Corner>& corners, const Eigen::VectorXd& r, int image) {
  double sum = 0.0;
  int n = 0;
  for (std::size_t i = 0; i < corners.size(); ++i)
    if (corners[i].image == image) {
      sum += r.segment<2>(2 * static_cast<Eigen::Index>(i)).squaredNorm();
      ++n;
    }
  return n ? std::sqrt(sum / n) : 0.0;
}

}  // namespace

StereoMarkerPose stereo_pose_from_markers(const std::vector<MonoBoardDetector::Marker>& left,
                                          const std::vector<MonoBoardDetector::Marker>& right,
                                          const MarkerLayout& layout, const StereoCamera& rectified) {
  StereoMarkerPose pose;
  std::vector<Corner> corners = corners_of(left, layout, 0);
  const std::vector<Corner> right_corners = corners_of(right, layout, 1);
  corners.insert(corners.end(), right_corners.begin(), right_corners.end());
  if (corners.size() < 4) return pose;

  // The start: the planar pose in the image with more markers, in the left frame.
  const bool from_right = right.size() > left.size();
  const MarkerPose start =
      pose_from_markers(from_right ? right : left, layout, from_right ? rectified.right : rectified.left);
  if (!start.found) return pose;
  Eigen::Isometry3d T = start.T_camera_board;
  if (from_right) T.translation().x() += rectified.baseline();  // the right camera sits at +B along x

  const std::array<Eigen::Matrix<double, 3, 4>, 2> P{rectified.left.projection_matrix,
                                                      rectified.right.projection_matrix};
  Eigen::VectorXd r = residuals(corners, P, T);
  double damping = 1e-3;
  for (int iteration = 0; iteration < 30; ++iteration) {
    // Jacobian by central differences: six columns of two projections each.
    Eigen::MatrixXd J(r.size(), 6);
    for (int k = 0; k < 6; ++k) {
      Eigen::Matrix<double, 6, 1> h = Eigen::Matrix<double, 6, 1>::Zero();
      h[k] = k < 3 ? 1e-7 : 1e-7 * std::max(1.0, T.translation().norm());
      J.col(k) = (residuals(corners, P, moved(T, h)) - residuals(corners, P, moved(T, -h))) / (2.0 * h[k]);
    }
    const Eigen::Matrix<double, 6, 6> JtJ = J.transpose() * J;
    const Eigen::Matrix<double, 6, 1> Jtr = J.transpose() * r;
    const Eigen::Matrix<double, 6, 6> damped = JtJ + damping * Eigen::Matrix<double, 6, 6>(JtJ.diagonal().asDiagonal());
    const Eigen::Matrix<double, 6, 1> step = -damped.ldlt().solve(Jtr);
    if (!step.allFinite()) break;
    const Eigen::Isometry3d candidate = moved(T, step);
    const Eigen::VectorXd r_candidate = residuals(corners, P, candidate);
    if (r_candidate.squaredNorm() < r.squaredNorm()) {
      T = candidate;
      r = r_candidate;
      damping = std::max(1e-9, damping * 0.1);
      if (step.head<3>().norm() < 1e-10 && step.tail<3>().norm() < 1e-9) break;
    } else {
      damping *= 10.0;
      if (damping > 1e6) break;
    }
  }
  pose.T_camera_board = T;
  pose.rms_left_px = rms_of(corners, r, 0);
  pose.rms_right_px = rms_of(corners, r, 1);
  pose.left_corners = static_cast<int>(corners.size() - right_corners.size());
  pose.right_corners = static_cast<int>(right_corners.size());
  // The board faces the camera: its z axis (out of the front face) points back at it.
  pose.found = T.translation().z() > 0.0 && T.linear().col(2).dot(T.translation()) < 0.0;
  return pose;
}

namespace {

std::vector<MonoBoardDetector::Marker> without_id(const std::vector<MonoBoardDetector::Marker>& markers, int id) {
  std::vector<MonoBoardDetector::Marker> rest;
  for (const auto& marker : markers)
    if (marker.id != id) rest.push_back(marker);
  return rest;
}

/// [px] rms of marker `id`'s corners in both images under pose T.
double marker_rms(const std::vector<MonoBoardDetector::Marker>& left, const std::vector<MonoBoardDetector::Marker>& right,
                  int id, const MarkerLayout& layout, const StereoCamera& rectified, const Eigen::Isometry3d& T) {
  double sum = 0.0;
  int n = 0;
  for (int image = 0; image < 2; ++image)
    for (const auto& marker : image ? right : left) {
      if (marker.id != id) continue;
      const auto board = board_corners(marker, layout);
      if (!board) continue;
      const auto& P = image ? rectified.right.projection_matrix : rectified.left.projection_matrix;
      for (std::size_t c = 0; c < 4; ++c, ++n) sum += (project(P, T * (*board)[c]) - marker.corners_px[c]).squaredNorm();
    }
  return n ? std::sqrt(sum / n) : 0.0;
}

}  // namespace

StereoMarkerPose robust_stereo_pose_from_markers(const std::vector<MonoBoardDetector::Marker>& left,
                                                 const std::vector<MonoBoardDetector::Marker>& right,
                                                 const MarkerLayout& layout, const StereoCamera& rectified,
                                                 const StereoMarkerPose& all, double limit_px, double min_outlier_px,
                                                 int& left_out_id) {
  left_out_id = -1;
  std::set<int> ids;
  for (const auto& marker : left) ids.insert(marker.id);
  for (const auto& marker : right) ids.insert(marker.id);
  if (!all.found || ids.size() < 4) return all;
  int worst = -1;
  StereoMarkerPose rest;
  for (const int id : ids) {
    const StereoMarkerPose pose = stereo_pose_from_markers(without_id(left, id), without_id(right, id), layout, rectified);
    if (pose.found && (worst < 0 || std::max(pose.rms_left_px, pose.rms_right_px) <
                                        std::max(rest.rms_left_px, rest.rms_right_px))) {
      worst = id;
      rest = pose;
    }
  }
  if (worst < 0) return all;
  const double rest_rms = std::max(rest.rms_left_px, rest.rms_right_px);
  const double odd_rms = marker_rms(left, right, worst, layout, rectified, rest.T_camera_board);
  if (rest_rms > limit_px || odd_rms <= std::max(min_outlier_px, 3.0 * rest_rms)) return all;
  left_out_id = worst;
  return rest;
}

}  // namespace l2s::detail
