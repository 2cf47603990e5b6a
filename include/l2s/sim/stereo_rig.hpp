#pragma once
// The simulated stereo camera: a rectified ideal pinhole pair like the
// Point Grey Bumblebee XB3 of the paper (1280x960, 12 cm baseline).

#include <l2s/camera.hpp>

#include <Eigen/Geometry>

namespace l2s::sim {

/// Pixel convention: pixel (u, v) covers [u - 0.5, u + 0.5] x [v - 0.5, v + 0.5],
/// so its centre sits at integer coordinates, as CameraInfo::project returns
/// them; the principal point is the image centre ((W - 1) / 2, (H - 1) / 2).
struct StereoRig {
  int width = 1280;             ///< [px]
  int height = 960;             ///< [px]
  double horizontal_fov = 0.7505;  ///< [rad] full horizontal field of view
  double baseline = 0.12;       ///< [m] right camera sits at -baseline along body y

  double fx() const;  ///< [px] (width / 2) / tan(fov / 2); square pixels
  double cx() const { return (width - 1) / 2.0; }   ///< [px]
  double cy() const { return (height - 1) / 2.0; }  ///< [px]

  /// left.yaml / right.yaml content (CameraInfo::ideal).
  StereoCamera cameras() const;
  /// Camera body <- optical frame of camera `index` (0 = left, 1 = right).
  Eigen::Isometry3d T_cambody_optical(int index) const;

  /// Throws ParamError naming the field.
  void validate() const;
};

}  // namespace l2s::sim
