#pragma once
// Roll, pitch and yaw with R = Rz(yaw) * Ry(pitch) * Rx(roll) (fixed axes X,
// then Y, then Z): the convention of ROS tf and of the paper's Table I.

#include <l2s/export.hpp>

#include <Eigen/Geometry>

namespace l2s {

/// (roll, pitch, yaw) [rad] of a rotation matrix; pitch in [-pi/2, pi/2].
L2S_EXPORT Eigen::Vector3d roll_pitch_yaw(const Eigen::Matrix3d& R);

/// The pose with rotation Rz(yaw) * Ry(pitch) * Rx(roll) [rad] and translation
/// t [m]; the inverse of roll_pitch_yaw() for the rotation, same argument order.
L2S_EXPORT Eigen::Isometry3d pose_from_roll_pitch_yaw(double roll, double pitch, double yaw, const Eigen::Vector3d& t);

}  // namespace l2s
