#include <l2s/camera.hpp>

#include <Eigen/Geometry>

#include <limits>

namespace l2s {

Eigen::Vector2d CameraInfo::project(const Eigen::Vector3d& p_left_optical) const {
  const Eigen::Vector3d h = projection_matrix * p_left_optical.homogeneous();
  if (!(h.z() > 0.0)) return Eigen::Vector2d::Constant(std::numeric_limits<double>::quiet_NaN());
  return h.head<2>() / h.z();
}

CameraInfo CameraInfo::ideal(const std::string& name, int width, int height, double fx, double cx,
                             double cy, double baseline_m) {
  CameraInfo camera;
  camera.camera_name = name;
  camera.width = width;
  camera.height = height;
  camera.camera_matrix << fx, 0, cx, 0, fx, cy, 0, 0, 1;
  camera.distortion_coefficients = {0.0, 0.0, 0.0, 0.0, 0.0};
  camera.projection_matrix << fx, 0, cx, -fx * baseline_m, 0, fx, cy, 0, 0, 0, 1, 0;
  return camera;
}

}  // namespace l2s
