#pragma once
// The simulated stereo camera. By default a rectified ideal pinhole pair like
// the Point Grey Bumblebee XB3 of the paper (1280x960, 12 cm baseline). A rig
// may also be what real pairs are: lenses with their own focal length, aspect
// and principal point, plumb_bob or equidistant distortion, and a right camera
// turned and shifted slightly off the ideal parallel mount. cameras() then
// reports the ROS camera_info a stereo calibrator would compute for it (K, D,
// R, P), and the renderer writes raw images (ImageKind::Raw) as the physical
// cameras see them.

#include <l2s/camera.hpp>
#include <l2s/export.hpp>
#include <l2s/sim/lens.hpp>

#include <Eigen/Geometry>
#include <array>

namespace l2s::sim {

/// Pixel convention: pixel (u, v) covers [u - 0.5, u + 0.5] x [v - 0.5, v + 0.5],
/// so its centre sits at integer coordinates, as CameraInfo::project returns
/// them; the nominal principal point is the image centre ((W - 1) / 2, (H - 1) / 2).
///
/// Frames: the camera body frame (x forward, y left, z up) has its origin at
/// the left camera's optical centre and is aligned with the left *physical*
/// camera of a level rig; a rolled rig turns both cameras about the left
/// optical axis (body x) by `roll`. The right physical camera sits at
/// T_left_right = [R(right_rotation) | (baseline, 0, 0) + right_offset] in the
/// left optical frame.
struct L2S_SIM_EXPORT StereoRig {
  int width = 1280;                ///< [px] 16..16384
  int height = 960;                ///< [px] 16..16384
  double horizontal_fov = 0.7505;  ///< [rad] nominal full horizontal field of view, (0.05, 3.0)
  double baseline = 0.12;          ///< [m] right camera sits at -baseline along body y, (0, 5)
  /// [rad] The rig turned about the left optical axis, any angle: users mount
  /// pairs on their side (90 deg) or upside down (180 deg). Right-handed
  /// about the forward axis: at +90 deg the camera's right points down (it
  /// turned clockwise, seen from behind) and what was right of the image
  /// centre appears above it.
  double roll = 0.0;

  // --- The physical pair (defaults: the ideal rectified pair of the paper) ---
  std::array<CameraLens, 2> lenses;  ///< left (0) and right (1) camera lens
  Eigen::Vector3d right_rotation = Eigen::Vector3d::Zero();  ///< [rad] rotation vector of R_left_right, norm <= 0.1
  Eigen::Vector3d right_offset = Eigen::Vector3d::Zero();    ///< [m] right optical centre minus (baseline, 0, 0), left optical frame, norm <= baseline / 2
  bool raw_images = false;  ///< write raw images also without distortion (raw whenever a lens has a distortion model)

  /// [px] nominal focal length of the ideal pinhole: (width / 2) / tan(fov / 2).
  double fx() const;
  double cx() const { return (width - 1) / 2.0; }   ///< [px] nominal principal point
  double cy() const { return (height - 1) / 2.0; }  ///< [px]

  /// True when nothing differs from the ideal rectified pair (lenses, mount).
  bool ideal() const;
  /// Raw when raw_images is set or a lens has a distortion model, else Rectified.
  ImageKind images() const;

  /// Physical camera matrix K of camera `index` (0 left, 1 right). A lens's
  /// fx is focal_scale * (width / 2) / d(tan(fov / 2)), d its radial
  /// distortion, so the raw image spans about the nominal field of view.
  Eigen::Matrix3d camera_matrix(int index) const;

  /// left.yaml / right.yaml content, as a ROS stereo calibration reports it.
  /// The ideal rig gives CameraInfo::ideal. Otherwise R rectifies each camera
  /// (Bouguet: each turned by half the relative rotation, then the baseline
  /// along x), and P is the pinhole of the rectified pair that, like the ROS
  /// calibrator's default alpha = 0, keeps only valid pixels: its window is
  /// the largest one with square pixels and the raw image size that lies
  /// inside both raw images, found from the undistorted raw borders and then
  /// checked pixel by pixel along the rectified border, so the rectified
  /// images have no invalid border anywhere. `images` is images().
  StereoCamera cameras() const;

  /// Camera body <- physical optical frame of camera `index` (0 = left, 1 = right).
  Eigen::Isometry3d T_cambody_optical(int index) const;
  /// Left physical optical frame <- the dataset's camera frame (DATASET.md):
  /// identity for raw images and for the ideal rig; for rectified images of
  /// a non-ideal rig, the inverse of the left rectification R.
  Eigen::Isometry3d T_optical_camera() const;

  /// [px] Where a point lands in the image that is written for camera
  /// `index`: through K and D for raw images, through R and P for rectified
  /// ones. NaN when the point is behind the camera or beyond where the lens
  /// model is one-to-one (it could not be imaged there).
  Eigen::Vector2d project(int index, const Eigen::Vector3d& p_cambody) const;
  /// The same for a point given in camera `index`'s physical optical frame.
  Eigen::Vector2d project_optical(int index, const Eigen::Vector3d& p_optical) const;

  /// Throws ParamError naming the field.
  void validate() const;

  /// A copy with the flaws of a typical real pair: focal lengths 0.4 % apart,
  /// fy / fx = 1.002, principal points a few pixels off centre, the right
  /// camera turned by about 0.3 deg and 1 mm off its nominal place, and
  /// typical_distortion(model) on both lenses. Raw images unless model is None.
  StereoRig with_real_lenses(DistortionModel model) const;
};

}  // namespace l2s::sim
