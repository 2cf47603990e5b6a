#pragma once
// The board's geometry for the calibration check (private to the library):
// distances to its contour, which points lie off it or behind it.

#include <l2s/target.hpp>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

namespace l2s::detail {

/// Median of `values`; NaN when empty.
inline double median(std::vector<double> values) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  const auto mid = values.begin() + values.size() / 2;
  std::nth_element(values.begin(), mid, values.end());
  return *mid;
}

/// Robust sigma (1.4826 times the median absolute deviation) of `values`
/// about `centre`; NaN when empty.
inline double robust_sigma(const std::vector<double>& values, double centre) {
  std::vector<double> deviations;
  deviations.reserve(values.size());
  for (const double v : values) deviations.push_back(std::abs(v - centre));
  return 1.4826 * median(std::move(deviations));
}

/// [m] Distance of a board-frame point from the nearest contour of the
/// board (outline or a hole rim), in its plane.
inline double contour_distance(const Eigen::Vector2d& q, const Target& target) {
  const double dx = std::abs(q.x()) - target.board_width / 2, dy = std::abs(q.y()) - target.board_height / 2;
  double d = (dx > 0 || dy > 0) ? Eigen::Vector2d(std::max(dx, 0.0), std::max(dy, 0.0)).norm() : -std::max(dx, dy);
  for (const auto& c : target.hole_centers()) d = std::min(d, std::abs((q - c).norm() - target.hole_radius));
  return d;
}

/// True when a board-frame point is off the board: beyond the outline or
/// inside a hole by more than `band` [m].
inline bool off_board(const Eigen::Vector2d& q, const Target& target, double band) {
  if (std::abs(q.x()) > target.board_width / 2 + band || std::abs(q.y()) > target.board_height / 2 + band) return true;
  for (const auto& c : target.hole_centers())
    if ((q - c).norm() < target.hole_radius - band) return true;
  return false;
}

/// True when the camera sees the board in front of `p_camera`: its ray
/// crosses the board's face (outside the holes) before reaching it. The
/// lidar sees the wall through the holes and past the edges from elsewhere.
inline bool behind_board(const Eigen::Vector3d& p_camera, const Eigen::Isometry3d& T_camera_board, const Target& target) {
  const Eigen::Vector3d n = T_camera_board.linear().col(2), o = T_camera_board.translation();
  const double along = n.dot(p_camera);
  if (std::abs(along) < 1e-9) return false;
  const double t = n.dot(o) / along;  // the ray p(t) = t * p_camera meets the plane at t
  constexpr double kBehind = 0.05;    // [m] board returns (on the plane, with noise) stay visible
  if (!(t > 0.0 && (1.0 - t) * p_camera.norm() > kBehind)) return false;
  const Eigen::Vector2d q = (T_camera_board.inverse() * (t * p_camera)).head<2>();
  return !off_board(q, target, 0.0);
}

/// True when `p_camera` lies on or near the board (within 0.3 m of its
/// plane, inside its outline grown by 0.2 m): what the fit made agree.
inline bool near_board(const Eigen::Vector3d& p_camera, const Eigen::Isometry3d& T_camera_board, const Target& target) {
  const Eigen::Vector3d q = T_camera_board.inverse() * p_camera;
  return std::abs(q.z()) < 0.3 && std::abs(q.x()) < target.board_width / 2 + 0.2 &&
         std::abs(q.y()) < target.board_height / 2 + 0.2;
}

}  // namespace l2s::detail
