#pragma once
// Depth discontinuities of a whole lidar sweep (private to the library): the
// near side of every range jump, where a silhouette edge of the scene lies.

#include <l2s/types.hpp>

#include <Eigen/Core>
#include <vector>

namespace l2s::detail {

/// When two neighbouring returns make a discontinuity.
struct JumpRule {
  double min_jump = 0.3;        ///< [m]
  double relative_jump = 0.05;  ///< share of the near range
  double gap_factor = 1.5;      ///< ring neighbours farther apart than this many azimuth steps: no return between
  double min_range = 0.5;       ///< [m] nearer returns are ignored

  bool jumps(double near_range, double far_range) const {
    return far_range - near_range >= std::max(min_jump, relative_jump * near_range);
  }
};

/// Along each ring in azimuth: a return whose neighbour is much farther, or
/// missing (a gap of several azimuth steps), is an edge. The edge is put
/// halfway (in azimuth) to that neighbour at the near return's range, which
/// removes the bias of the last return (up to one step inside the object).
std::vector<Eigen::Vector3d> ring_discontinuities(const LidarCloud& cloud, const JumpRule& rule);

/// For clouds without rings: the nearest return of each cell of a spherical
/// grid (azimuth x elevation, `step` [rad]) against its four neighbours. An
/// empty neighbour says nothing (sparse patterns leave holes everywhere).
std::vector<Eigen::Vector3d> grid_discontinuities(const LidarCloud& cloud, const JumpRule& rule, double step);

}  // namespace l2s::detail
