#pragma once
// The board frame of target.hpp from a detection (private to the library).

#include <l2s/geometry.hpp>
#include <l2s/target.hpp>

#include <Eigen/Geometry>

namespace l2s::detail {

/// T_sensor_board from four labelled hole centres on the sensor-facing face:
/// the pattern is centred on the board and its rows run along board x; z
/// points out of the face towards the sensor at the origin.
inline Eigen::Isometry3d board_pose_from_centers(const HoleCenters& c, const Plane& plane) {
  const auto tl = static_cast<int>(Hole::TopLeft), tr = static_cast<int>(Hole::TopRight);
  const auto bl = static_cast<int>(Hole::BottomLeft), br = static_cast<int>(Hole::BottomRight);
  Eigen::Vector3d z = plane.normal();
  const Eigen::Vector3d center = (c[tl] + c[tr] + c[bl] + c[br]) / 4.0;
  if (z.dot(center) > 0.0) z = -z;
  Eigen::Vector3d x = (c[tr] - c[tl]) + (c[br] - c[bl]);
  x = (x - x.dot(z) * z).normalized();
  Eigen::Isometry3d T_sensor_board = Eigen::Isometry3d::Identity();
  T_sensor_board.linear().col(0) = x;
  T_sensor_board.linear().col(1) = z.cross(x);
  T_sensor_board.linear().col(2) = z;
  T_sensor_board.translation() = center;
  return T_sensor_board;
}

/// The target's hole centres (front face) where `T_sensor_board` puts its board.
inline HoleCenters hole_centres_at(const Target& target, const Eigen::Isometry3d& T_sensor_board) {
  HoleCenters centres{};
  const auto holes = target.hole_centers();
  for (std::size_t h = 0; h < 4; ++h) centres[h] = T_sensor_board * Eigen::Vector3d(holes[h].x(), holes[h].y(), 0.0);
  return centres;
}

}  // namespace l2s::detail
