#include "sim/pixel_rays.hpp"

#include "sim/rectification.hpp"

#include <limits>

namespace l2s::sim::detail {

PixelRays::PixelRays(const StereoRig& rig, int index) {
  const Eigen::Isometry3d T = rig.T_cambody_optical(index);
  origin_ = T.translation();
  R_cambody_normal_ = T.linear();
  if (rig.images() == ImageKind::Raw) {
    const Eigen::Matrix3d K = rig.camera_matrix(index);
    fx_ = K(0, 0), fy_ = K(1, 1), cx_ = K(0, 2), cy_ = K(1, 2);
    distortion_ = rig.lenses[static_cast<std::size_t>(index)].distortion;
  } else if (rig.ideal()) {
    // Kept apart so the paper suite's rays stay bit for bit what they were.
    fx_ = fy_ = rig.fx();
    cx_ = rig.cx(), cy_ = rig.cy();
  } else {
    // A rectified pixel looks along R^T K_rect^-1 (u, v, 1) in the physical camera.
    const Rectification rect = rectify(rig);
    R_cambody_normal_ = T.linear() * rect.R_rect_optical[static_cast<std::size_t>(index)].transpose();
    fx_ = rect.K(0, 0), fy_ = rect.K(1, 1), cx_ = rect.K(0, 2), cy_ = rect.K(1, 2);
  }
}

Eigen::Vector3d PixelRays::direction(double u, double v) const {
  Eigen::Vector2d normal = Eigen::Vector2d::Constant(std::numeric_limits<double>::quiet_NaN());
  return direction(u, v, &normal);
}

Eigen::Vector3d PixelRays::direction(double u, double v, Eigen::Vector2d* normal) const {
  Eigen::Vector2d n((u - cx_) / fx_, (v - cy_) / fy_);
  if (distortion_.model != DistortionModel::None) {
    n = normal->allFinite() ? distortion_.undistort(n, *normal) : distortion_.undistort(n);
    *normal = n;
  }
  return (R_cambody_normal_ * Eigen::Vector3d(n.x(), n.y(), 1.0)).normalized();
}

}  // namespace l2s::sim::detail
