#pragma once
// The paper's parametrisation of a sensor setting (DATASET.md, "The paper's
// parametrisation of a setting") and the nine settings of its Table I.

#include <l2s/export.hpp>

#include <Eigen/Geometry>

namespace l2s::sim {

/// Pose of the lidar in the camera body frame (x forward, y left, z up, origin
/// at the left camera's optical centre): p_cambody = R * p_lidar + t with
/// R = Rz(yaw) * Ry(pitch) * Rx(roll).
struct L2S_SIM_EXPORT SensorSetting {
  double tx = 0.0;     ///< [m]
  double ty = 0.0;     ///< [m]
  double tz = 0.0;     ///< [m]
  double yaw = 0.0;    ///< [rad] psi, about body z
  double pitch = 0.0;  ///< [rad] theta, about body y
  double roll = 0.0;   ///< [rad] phi, about body x

  Eigen::Isometry3d T_cambody_lidar() const;
  /// The ground truth of DATASET.md: inverse(T_cambody_lidar) * T_cambody_optical.
  Eigen::Isometry3d T_lidar_camera() const;
};

/// Setting 1..9 of the paper's Table I; throws ParamError("setting", ...) otherwise.
L2S_SIM_EXPORT SensorSetting paper_setting(int index);

/// Body <- left optical frame: x_opt = -y_body, y_opt = -z_body, z_opt = x_body.
L2S_SIM_EXPORT Eigen::Isometry3d T_cambody_optical();

/// R = Rz(yaw) * Ry(pitch) * Rx(roll) (fixed axes X, then Y, then Z).
L2S_SIM_EXPORT Eigen::Matrix3d rotation_zyx(double yaw, double pitch, double roll);

}  // namespace l2s::sim
