#pragma once
// Whether a stereo pair's coarse disparity shows the board where its markers
// put it. The calibration check measures the scene's depth by the pair's
// disparity; on a plain board, a plain wall or through a short baseline that
// disparity can tilt or shift the board by centimetres, and it may serve as
// the check's evidence only where it agrees with the markers' pose.

#include <l2s/geometry.hpp>
#include <l2s/target.hpp>

#include <Eigen/Geometry>

#include <string>

namespace l2s::detail {

struct MarkerDepthAgreement {
  bool agrees = false;
  int face_points = 0;         ///< coarse points whose rays meet the board's face
  double tilt_deg = 0.0;       ///< [deg] between the plane they fit and the markers' board
  double offset = 0.0;         ///< [m] of that plane from the board's centre, along the board's normal
  std::string summary;         ///< one line for the branch's note
};

/// `cloud`: the coarse stereo cloud (left rectified frame); `T_camera_board`:
/// the markers' board pose in that frame. The points whose viewing rays meet
/// the board's face (inside its outline, clear of its holes by `margin`) are
/// fitted with a plane, after dropping those whose depth lies far from the
/// rest (three robust sigmas, and a quarter of a hole radius). It agrees when at least `min_points` fit and
/// their plane is tilted no more than `max_tilt_deg` from the board and lies
/// within half a hole radius of its centre: a board found in that depth
/// would put its holes where the markers do.
MarkerDepthAgreement marker_depth_agreement(const StereoCloud& cloud, const Eigen::Isometry3d& T_camera_board,
                                            const Target& target, double max_tilt_deg = 5.0,
                                            int min_points = 30, double margin = 0.03);

}  // namespace l2s::detail
