#pragma once
// The ray of every image point of one simulated camera: through the
// rectified pinhole (R and P) for rectified images, through the physical
// lens (K and D, undistorted by Newton's method) for raw images.

#include <l2s/sim/stereo_rig.hpp>

#include <Eigen/Core>

namespace l2s::sim::detail {

class PixelRays {
 public:
  PixelRays(const StereoRig& rig, int index);

  /// Optical centre, camera body frame.
  const Eigen::Vector3d& origin() const { return origin_; }
  /// Unit direction (camera body frame) through image point (u, v) [px].
  Eigen::Vector3d direction(double u, double v) const;
  /// The same, undistorting from `*normal` (the normalised coordinates of a
  /// nearby point, NaN for none) and storing this point's there: along a row
  /// Newton then needs two steps instead of five.
  Eigen::Vector3d direction(double u, double v, Eigen::Vector2d* normal) const;
  /// [rad] angle one pixel spans near the image centre.
  double pixel_angle() const { return 1.0 / fx_; }
  /// [px] principal point of the written image.
  Eigen::Vector2d principal_point() const { return {cx_, cy_}; }

 private:
  Eigen::Vector3d origin_;
  Eigen::Matrix3d R_cambody_normal_;  ///< body <- the frame of the normalised coordinates
  double fx_ = 1.0, fy_ = 1.0, cx_ = 0.0, cy_ = 0.0;
  LensDistortion distortion_;  ///< model None for rectified images
};

}  // namespace l2s::sim::detail
