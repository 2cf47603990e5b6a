#pragma once
// Lens models of the simulated cameras, in the two forms ROS camera_info
// names: `plumb_bob` (Brown-Conrady radial k1 k2 k3 and tangential p1 p2 on
// the pinhole's normalised coordinates, as in OpenCV's calib3d) and
// `equidistant` (the angle of a ray to the axis, polynomial k1..k4 in it, as
// in OpenCV's fisheye module). Both act on normalised coordinates
// (x, y) = (X / Z, Y / Z) of a point in the camera's optical frame.

#include <l2s/export.hpp>

#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

namespace l2s::sim {

enum class DistortionModel {
  None,         ///< ideal pinhole
  PlumbBob,     ///< ROS `plumb_bob`: k1 k2 p1 p2 k3
  Equidistant,  ///< ROS `equidistant`: k1 k2 k3 k4 on the ray angle
};

/// "none", "plumb_bob", "equidistant"; throws ParamError naming `field` on other names.
L2S_SIM_EXPORT DistortionModel distortion_model_from_name(const std::string& name, const std::string& field);
L2S_SIM_EXPORT const char* name_of(DistortionModel model);

/// A lens distortion in normalised coordinates.
struct L2S_SIM_EXPORT LensDistortion {
  DistortionModel model = DistortionModel::None;
  /// plumb_bob: k1 k2 p1 p2 k3; equidistant: k1 k2 k3 k4 (the fifth is unused and must be 0).
  std::array<double, 5> coefficients{};

  bool distorts() const;  ///< any coefficient non-zero (None always false)

  /// Undistorted -> distorted normalised coordinates (what the lens does).
  Eigen::Vector2d distort(const Eigen::Vector2d& undistorted) const;
  /// The inverse of distort() by Newton's method from `guess` (the distorted
  /// point when none is given), to 1e-13. Points beyond the fold (see
  /// max_radius) have no inverse; the result is then the last iterate.
  Eigen::Vector2d undistort(const Eigen::Vector2d& distorted) const;
  Eigen::Vector2d undistort(const Eigen::Vector2d& distorted, const Eigen::Vector2d& guess) const;

  /// Distorted radius of an undistorted radius r on the x axis, radial terms
  /// only (tan(angle) -> image radius; the identity for None).
  double radial(double r) const;
  /// True when radial() rises strictly on [0, r]: a point at undistorted
  /// radius r is imaged where the lens puts it, not folded back into the image.
  bool one_to_one_up_to(double r) const;

  /// The ROS `distortion_model` string ("plumb_bob" also for None) and its
  /// coefficients (5 for plumb_bob, 4 for equidistant).
  std::string ros_model() const;
  std::vector<double> ros_coefficients() const;

  /// Throws ParamError naming `field` for non-finite or implausibly large coefficients.
  void validate(const std::string& field) const;
};

/// A distortion of typical size for a lens of `horizontal_fov` [rad]: barrel
/// distortion that grows with the field of view (plumb_bob k1 -0.08 at 40 deg
/// to -0.30 at 100 deg, with k2 keeping the profile monotonic, and small
/// tangential terms; equidistant coefficients of a few hundredths).
L2S_SIM_EXPORT LensDistortion typical_distortion(DistortionModel model, double horizontal_fov);

/// What makes one physical camera of a pair differ from the rig's nominal
/// pinhole (StereoRig::horizontal_fov and the image centre).
struct L2S_SIM_EXPORT CameraLens {
  double focal_scale = 1.0;  ///< fx relative to the nominal fx of the rig, 0.8..1.25
  double aspect = 1.0;       ///< fy / fx, 0.95..1.05 (real sensors: within ~1 %)
  Eigen::Vector2d principal_offset = Eigen::Vector2d::Zero();  ///< [px] principal point minus the image centre
  LensDistortion distortion;

  /// True when the lens is the nominal ideal pinhole.
  bool ideal() const;
  /// Throws ParamError naming `field` (e.g. "camera.left").
  void validate(const std::string& field, int width, int height) const;
};

}  // namespace l2s::sim
