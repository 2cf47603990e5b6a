#pragma once
// Calibration error against ground truth (DATASET.md, Geiger et al. 2012).

#include <l2s/export.hpp>

#include <Eigen/Geometry>

namespace l2s {

struct PoseError {
  double translation = 0.0;  ///< [m] e_t = |t - t_true|
  double rotation = 0.0;     ///< [rad] e_r = angle of R^-1 * R_true
};

/// e_t and e_r of an estimate of T_lidar_camera against the truth.
L2S_EXPORT PoseError pose_error(const Eigen::Isometry3d& T_estimate, const Eigen::Isometry3d& T_true);

}  // namespace l2s
