#include <l2s/sim/settings.hpp>

#include <l2s/error.hpp>

#include <array>
#include <string>

namespace l2s::sim {

Eigen::Matrix3d rotation_zyx(double yaw, double pitch, double roll) {
  return (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

Eigen::Isometry3d T_cambody_optical() {
  // Columns are the optical axes in body coordinates: x_opt = -y_body,
  // y_opt = -z_body, z_opt = +x_body.
  Eigen::Matrix3d R;
  R << 0, 0, 1,  //
      -1, 0, 0,  //
      0, -1, 0;
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = R;
  return T;
}

Eigen::Isometry3d SensorSetting::T_cambody_lidar() const {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = rotation_zyx(yaw, pitch, roll);
  T.translation() = Eigen::Vector3d(tx, ty, tz);
  return T;
}

Eigen::Isometry3d SensorSetting::T_lidar_camera() const {
  return T_cambody_lidar().inverse() * T_cambody_optical();
}

SensorSetting paper_setting(int index) {
  // The paper's Table I: tx ty tz [m] | yaw pitch roll [rad].
  static const std::array<SensorSetting, 9> table{{
      {-0.8, -0.1, 0.4, 0.0, 0.0, 0.0},
      {0.0, 0.0, 0.0, 0.5, 0.0, 0.0},
      {0.0, 0.0, 0.0, 0.3, 0.1, 0.2},
      {-0.3, 0.2, -0.2, 0.3, -0.1, 0.2},
      {0.0, 0.0, 0.0, 0.0, 0.1, 0.0},
      {0.0, 0.0, 0.0, 0.0, 0.0, 0.4},
      {0.0, 0.0, 0.0, 0.0, 0.0, 0.0},
      {-0.128, 0.418, -0.314, -0.103, -0.299, 0.110},
      {-0.433, 0.845, 1.108, -0.672, 0.258, 0.075},
  }};
  if (index < 1 || index > 9)
    throw ParamError("setting", "must be 1..9 (Table I), got " + std::to_string(index));
  return table[static_cast<std::size_t>(index - 1)];
}

}  // namespace l2s::sim
