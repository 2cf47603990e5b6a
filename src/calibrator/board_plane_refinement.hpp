#pragma once
// Refines a centre-based T_target_source with the board planes both sensors
// fitted (private; the lidar-lidar facade). The hole centres of a ring lidar
// carry a bias per pose (where its rings happen to cross the holes; noise
// does not average it out), which the joint fit of the centres passes on,
// mostly into roll and pitch (the board poses differ little in height). The
// board plane of a lidar rests on thousands of points per sweep: its normal
// and offset fix the rotation about every axis but the normal, and the
// translation along it, far better. One weighted least-squares fit of
// centres, normals and offsets (Gauss-Newton from the centre fit).

#include <l2s/geometry.hpp>

#include <Eigen/Geometry>
#include <vector>

namespace l2s::detail {

/// One board pose as both sensors saw it.
struct BoardPoseObservation {
  HoleCenters target{};  ///< [m] clustered centres, target frame
  HoleCenters source{};  ///< [m] source frame, labelled alike
  Plane plane_target;    ///< the board's front face, normal towards the sensor
  Plane plane_source;
};

/// How much each kind of residual is trusted (1-sigma). The defaults are the
/// errors measured against ground truth on simulated VLP-16 / HDL-32E poses
/// (K = 1, 10 frames a pose): clustered centres about 1 mm per coordinate,
/// pose-averaged normals 0.01-0.08 deg apart, offsets within 0.8 mm. Tried
/// on 12 seeds: 3/0.5/1 and 2/0.6/0.5 (mm/mrad/mm) gave median e_r 0.043
/// and 0.037 deg, these 0.033 deg.
struct BoardPlaneWeights {
  double centre_sigma = 0.001;   ///< [m] per coordinate of a clustered centre (its bias, not its noise)
  double normal_sigma = 0.0006;  ///< [rad] of a board normal averaged over a pose
  double offset_sigma = 0.0005;  ///< [m] of a board plane's distance from the sensor
  /// [m] more for a source centre along the source sensor's line of sight
  /// to it: a camera measures depth far worse than direction (0: isotropic)
  double source_depth_sigma = 0.0;
  int iterations = 10;           ///< Gauss-Newton steps (it converges in 2-3 from the centre fit)
};

/// T_target_source fitting target ~ T * source for the centres, the normals
/// and the offsets of every pose, starting from `T0`. Returns T0 when the
/// system is singular (no poses).
Eigen::Isometry3d refine_with_board_planes(const Eigen::Isometry3d& T0,
                                           const std::vector<BoardPoseObservation>& poses,
                                           const BoardPlaneWeights& weights = {});

/// The mean of several fits of one plane (normals towards the sensor).
Plane mean_plane(const std::vector<Plane>& planes);

}  // namespace l2s::detail
