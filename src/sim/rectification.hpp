#pragma once
// Stereo rectification of a simulated rig, computed as a stereo calibrator
// does (Bouguet's method, as in OpenCV's stereoRectify): rotations that make
// both cameras parallel with the baseline along x, and one pinhole for both
// rectified images whose window holds only valid pixels (alpha = 0).

#include <l2s/sim/stereo_rig.hpp>

#include <Eigen/Core>
#include <array>

namespace l2s::sim::detail {

struct Rectification {
  std::array<Eigen::Matrix3d, 2> R_rect_optical;  ///< rectified <- physical optical frame, per camera
  Eigen::Matrix3d K = Eigen::Matrix3d::Identity();  ///< rectified pinhole shared by both images
  double baseline = 0.0;                            ///< [m] distance between the optical centres
};

/// The rotations alone (cheap, closed form).
std::array<Eigen::Matrix3d, 2> rectifying_rotations(const StereoRig& rig);

/// Rotations and the rectified pinhole. Raw borders are sampled every pixel
/// when a lens distorts and only at the corners otherwise (edges of an
/// undistorted image stay straight lines under a rotation). Throws ParamError
/// when the cameras share no rectified view.
Rectification rectify(const StereoRig& rig);

/// rectify(rig), remembered per thread for the last rig asked about: for
/// callers that project many points one by one (the placement search).
const Rectification& rectify_cached(const StereoRig& rig);

/// [px] Raw pixel of camera `index` seen along direction `ray_optical` (its
/// physical optical frame), through K and D; NaN behind the camera or beyond
/// where the lens is one-to-one.
Eigen::Vector2d raw_pixel(const StereoRig& rig, int index, const Eigen::Vector3d& ray_optical);

/// Normalised undistorted coordinates of raw pixel (u, v) of camera `index`.
Eigen::Vector2d undistorted_normal(const StereoRig& rig, int index, double u, double v);

}  // namespace l2s::sim::detail
