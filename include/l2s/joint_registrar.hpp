#pragma once
// Registration over several board poses: one rigid fit to all pose-wise
// labelled centre pairs (4 per pose), robust to one or more outlying poses,
// with per-DoF uncertainty and a leave-one-pose-out check (issue 9). Any two
// observation streams feed it (lidar and stereo camera, later a mono camera
// or a second lidar): `target` and `source` are the two sensors' centres.
// One pose gives exactly Registrar's result (the paper's two steps).

#include <l2s/export.hpp>
#include <l2s/fit_uncertainty.hpp>
#include <l2s/geometry.hpp>
#include <l2s/registrar.hpp>

#include <Eigen/Geometry>
#include <array>
#include <string>
#include <vector>

namespace l2s {

/// The centroids one board pose gave the two sensors, labelled alike.
struct PosePair {
  HoleCenters target{};  ///< [m] target sensor frame (the lidar for T_lidar_camera)
  HoleCenters source{};  ///< [m] source sensor frame (the camera)
  /// What the source's detection of this pose shares across its four
  /// centres beyond Params' pose bias, as the covariance of a rigid motion
  /// (dt, dphi) about their centroid, source frame: e.g. a stereo camera's
  /// depth and tilt error, which grows with the square of the range.
  /// Zero: nothing more.
  MotionCovariance source_bias = MotionCovariance::Zero();
};

/// Thread safety: immutable after construction; estimate() may run concurrently.
class L2S_EXPORT JointRegistrar {
 public:
  struct Params {
    /// A pose is an outlier when its residual under the fit of the other
    /// poses exceeds this many times what that fit predicts there (its
    /// residual noise and its spread at the pose), > 1
    double outlier_ratio = 3.0;
    double outlier_floor = 0.01;  ///< [m] and exceeds this rms (noise alone never rejects), >= 0
    int min_poses_to_reject = 3;  ///< fewer poses: no majority to judge by, nothing is rejected, >= 3
    /// condition of the fit (FitUncertainty::condition) above which a
    /// suggestion for another pose is made, > 1
    double max_condition = 8.0;
    /// The error each pose's detection shares across its four centres (a
    /// depth or tilt bias of the pose, which no residual shows), as a rigid
    /// motion about the pose's centroid: per axis, translation [m] and
    /// rotation [rad], >= 0. Added to the fit's uncertainty for every number
    /// of poses (three or more also get the jackknife, and the larger wins).
    /// From the poses suite (VLP-16, K = 1, 10 frames a pose): one pose's
    /// fit is off by 1.0e-3 rad rms per axis, and the shared error averages
    /// down over poses roughly as independent per pose.
    double pose_bias_translation = 0.0005;
    double pose_bias_rotation = 0.001;

    /// Throws ParamError naming the first invalid field.
    void validate() const;
  };

  /// How far leaving one pose out moves the estimate.
  struct LeaveOneOut {
    int pose = 0;               ///< index into the input poses
    bool found = false;         ///< the fit without it succeeded
    double translation = 0.0;   ///< [m] |t_without - t|
    double rotation = 0.0;      ///< [rad] angle of R_without^-1 R
    std::array<double, 6> shift{};  ///< [m m m rad rad rad] (tx ty tz roll pitch yaw) without minus with
  };

  struct Result {
    bool found = false;
    std::string reason;          ///< why not, when !found
    Eigen::Isometry3d T_target_source = Eigen::Isometry3d::Identity();
    std::vector<bool> used;      ///< per input pose: in the final fit (false: rejected as an outlier)
    std::vector<double> pose_rms;  ///< [m] per input pose, residual rms under the final fit (rejected ones too)
    std::vector<std::array<double, 4>> residuals;  ///< [m] per input pose and hole, |target - T source|
    double rms = 0.0;            ///< [m] over the used poses
    std::vector<std::string> notes;  ///< rejected poses and why
    Registrar::Result single;    ///< one used pose: Registrar's result (its translation-only step too)
    FitUncertainty uncertainty;  ///< of the final fit; three or more poses: widened by the jackknife over poses
    std::vector<LeaveOneOut> leave_one_out;  ///< one per used pose, when two or more are used
    int used_count() const;
  };

  JointRegistrar() : JointRegistrar(Params{}) {}
  /// Throws ParamError naming the field when `params` is invalid.
  explicit JointRegistrar(Params params) : JointRegistrar(params, Registrar::Params{}) {}
  /// `registrar`: degeneracy limits for each pose (one pose: the whole fit).
  JointRegistrar(Params params, Registrar::Params registrar);
  const Params& params() const { return params_; }

  /// Fits T_target_source to all poses. Never throws on bad data.
  Result estimate(const std::vector<PosePair>& poses) const;

 private:
  Params params_;
  Registrar::Params registrar_;
};

}  // namespace l2s
