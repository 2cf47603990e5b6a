#pragma once
// Board evidence from a cloud seen from its origin (private): a lidar sweep
// (with or without rings), or any cloud whose points lie along rays from the
// sensor. A return on the board plane inside a hole blocks it; a return well
// behind the plane whose ray crosses a hole sees through it. The same test on
// a band just outside the board's outline tells a free-standing board from a
// window of a larger surface. A hole with nothing behind it within range
// (open space) gives no return at all; a cloud dense all over (seconds of a
// ring-free scan) then shows it by the returns it lacks: the board's face
// around the hole says how many a solid surface there would have given.

#include <l2s/board_verifier.hpp>
#include <l2s/geometry.hpp>
#include <l2s/target.hpp>

#include <Eigen/Geometry>
#include <vector>

namespace l2s::detail {

struct CloudEvidenceParams {
  double on_plane = 0.05;  // [m] a return within this of the plane (along its ray) lies on it
  double behind = 0.15;    // [m] a return at least this far behind the plane sees past it
  /// The cloud samples the board all over (a ring-free accumulation, not a
  /// ring lidar's rows that may pass between the holes): each hole's
  /// returns missing against the face's density count as seeing through it.
  bool count_missing_returns = false;
};

/// Counts the samples of `points` (sensor frame; NaN allowed) for a board at
/// T_sensor_board; fit_rms/fit_scale are left for the caller.
BoardEvidence cloud_evidence(const std::vector<Eigen::Vector3d>& points, const Plane& plane,
                             const Eigen::Isometry3d& T_sensor_board, const Target& target,
                             const BoardVerifier::Params& verifier, const CloudEvidenceParams& params);

}  // namespace l2s::detail
