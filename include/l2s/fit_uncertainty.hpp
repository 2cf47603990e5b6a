#pragma once
// How well labelled point pairs fix a rigid transform: per-DoF uncertainty
// from the residuals and the Jacobian of the fit (covariance s^2 (J^T J)^-1,
// s^2 from the residuals over their degrees of freedom), the fit's weakest
// direction and which kind of extra board pose would constrain it most.

#include <l2s/export.hpp>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <string>
#include <vector>

namespace l2s {

/// Names of the six degrees of freedom, in the order of every array below.
L2S_EXPORT const std::array<const char*, 6>& dof_names();  // tx ty tz roll pitch yaw

/// Uncertainty of T_target_source = pose_from_roll_pitch_yaw(roll, pitch, yaw, t).
struct FitUncertainty {
  bool valid = false;          ///< false: too few pairs or a singular fit (reason says which)
  std::string reason;
  int pairs = 0;               ///< point pairs used
  int dof = 0;                 ///< 3 * pairs - 6
  double sigma_residual = 0.0; ///< [m] s, the residual standard error per coordinate
  std::array<double, 6> sigma{};     ///< [m m m rad rad rad] 1-sigma per DoF (tx ty tz roll pitch yaw)
  std::array<double, 6> bound_95{};  ///< [m m m rad rad rad] half width of the 95 % interval (Student t with dof)
  /// [m m m rad rad rad] Jackknife over board poses (JointRegistrar, three
  /// or more poses; else 0): errors a pose shares across its four centres
  /// (a depth or tilt bias of its detection) leave no residual, but move the
  /// estimate when that pose is left out. When set, sigma and bound_95 are
  /// the larger of the residual-based value and this one (its bound with
  /// Student t of poses - 1 dof).
  std::array<double, 6> sigma_between_poses{};
  /// [m m m rad rad rad] The part of sigma from an error each group of pairs
  /// shares (add_shared_group_error; JointRegistrar: each board pose); 0 when
  /// not modelled. sigma is the residual-based value and this in quadrature.
  std::array<double, 6> sigma_shared{};
  Eigen::Matrix<double, 6, 6> covariance = Eigen::Matrix<double, 6, 6>::Zero();  ///< [SI] of (tx ty tz roll pitch yaw)
  /// sqrt(lambda_max / lambda_min) of J^T J with rotations scaled by the
  /// points' mean range (so a radian and a metre at the board weigh alike).
  double condition = 0.0;
  Eigen::Matrix<double, 6, 1> weakest = Eigen::Matrix<double, 6, 1>::Zero();  ///< unit eigenvector of lambda_min, scaled units
  std::string weakest_summary;  ///< the weakest direction in words, e.g. "yaw with ty"
  std::string suggestion;       ///< the kind of pose that adds most along it, e.g. "farther away"
};

/// Evaluates the fit `T_target_source` of `target[i]` ~ T * `source[i]`
/// (finite pairs only). Never throws on bad data.
L2S_EXPORT FitUncertainty fit_uncertainty(const std::vector<Eigen::Vector3d>& target,
                                          const std::vector<Eigen::Vector3d>& source,
                                          const Eigen::Isometry3d& T_target_source);

/// Adds to `u` an error that each group of pairs shares and no residual shows
/// (the four centres of one board pose: a depth or tilt bias of its
/// detection): an independent rigid motion of each group's points about their
/// centroid, `sigma_t` [m] and `sigma_r` [rad] per axis, propagated through
/// the linearised fit. Updates covariance, sigma, bound_95 (the residual part
/// with Student t, this part with the normal quantile) and sigma_shared.
/// Groups index `source` as given to fit_uncertainty; nothing when `u` is not valid.
L2S_EXPORT void add_shared_group_error(FitUncertainty& u, const Eigen::Isometry3d& T_target_source,
                                       const std::vector<std::vector<Eigen::Vector3d>>& source_groups,
                                       double sigma_t, double sigma_r);

/// [m^2, rad^2] Covariance of a rigid motion (dt, dphi) of a group of points
/// about their centroid.
using MotionCovariance = Eigen::Matrix<double, 6, 6>;

/// As above with each group's own covariance of its motion, target frame
/// (e.g. a stereo camera's depth and tilt error, along and across its line
/// of sight, which grows with the square of the range); one per group.
L2S_EXPORT void add_shared_group_error(FitUncertainty& u, const Eigen::Isometry3d& T_target_source,
                                       const std::vector<std::vector<Eigen::Vector3d>>& source_groups,
                                       const std::vector<MotionCovariance>& motion_covariances);

/// [m] The rms of |target - T source| expected for new pairs at `source`
/// (source frame) under the fit `u` of T: the residual noise of the fit's
/// pairs plus the spread of its prediction there. 0 when `u` is not valid.
L2S_EXPORT double prediction_rms(const FitUncertainty& u, const Eigen::Isometry3d& T_target_source,
                                 const std::vector<Eigen::Vector3d>& source);

/// [rad] The 95 % bound of the rotation as one angle: the norm of its
/// per-DoF bounds taken as a rotation vector (with their correlations), free
/// of the roll-pitch-yaw parametrisation: near pitch +-90 deg roll and yaw
/// trade off, each uncertain by far more than the rotation is. 0 when `u`
/// is not valid.
L2S_EXPORT double rotation_bound_95(const FitUncertainty& u, const Eigen::Isometry3d& T_target_source);

/// [m] The norm of the three translation bounds; 0 when `u` is not valid.
L2S_EXPORT double translation_bound_95(const FitUncertainty& u);

/// Two-sided 95 % quantile of Student's t with `dof` degrees of freedom (>= 1).
L2S_EXPORT double student_t_95(int dof);

}  // namespace l2s
