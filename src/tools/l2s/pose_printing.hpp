#pragma once
// What `l2s calibrate` prints of a fit over board poses, the same for every
// pair of sensors (lidar-camera, lidar-lidar).

#include <l2s/joint_registrar.hpp>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <vector>

namespace l2s::cli {

/// One line: translation [m] and roll, pitch, yaw [rad] of T.
void print_pose(const char* label, const Eigen::Isometry3d& T);

/// Per-DoF uncertainty, the leave-one-pose-out shifts (numbered among all
/// poses; `used`: which joined the fit) and, for a poorly conditioned fit,
/// the pose that would help most.
void print_uncertainty(const JointRegistrar::Result& joint, const std::vector<bool>& used);

/// The board poses: how many, which frames moved, which pose was left out.
/// `Result`: Calibrator::Result or LidarPairCalibrator::Result.
template <class Result>
void print_poses(const Result& result) {
  std::printf("poses     %zu found, %d used; %zu frames skipped while the board moved\n", result.poses.size(),
              result.poses_used(), result.moving_frames.size());
  for (std::size_t p = 0; p < result.poses.size(); ++p) {
    const auto& pose = result.poses[p];
    std::printf("  pose %zu  frames %d-%d (%zu)", p, pose.first_frame, pose.last_frame, pose.frames.size());
    if (std::isfinite(pose.rms)) std::printf("  rms %.2f mm", pose.rms * 1e3);
    if (!pose.used) std::printf("  not used: %s", pose.reason.c_str());
    std::printf("\n");
  }
}

/// Which of `poses` joined the fit.
template <class Poses>
std::vector<bool> used_poses(const Poses& poses) {
  std::vector<bool> used;
  for (const auto& pose : poses) used.push_back(pose.used);
  return used;
}

}  // namespace l2s::cli
