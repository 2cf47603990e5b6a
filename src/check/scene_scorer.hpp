#pragma once
// The scores of one transform against the observed frames (private to the
// library): edge alignment, depth agreement and board consistency.

#include "check/left_view.hpp"

#include <l2s/calibration_check.hpp>

#include <array>
#include <limits>
#include <vector>

namespace l2s::detail {

/// Raw edge-kernel sums of one transform.
struct EdgeSums {
  double board = 0.0;  ///< sum of kernel values of the board edges inside the image
  double scene = 0.0;  ///< the same, edges off the board
  int board_seen = 0;  ///< board edges inside the image
  int scene_seen = 0;  ///< scene edges inside the image
};

class SceneScorer {
 public:
  /// Keeps references to `frames`; scores at most params.max_edge_frames of
  /// them (evenly spread) for edges and depth, every frame for the board.
  SceneScorer(const std::vector<CheckFrame>& frames, const LeftView& view, const Target& target,
              const CalibrationCheck::Params& params);

  /// Kernels of edge_sigma_px * 2^level, for a coarse-to-fine search.
  static constexpr int kLevels = 3;
  EdgeSums edges(const Eigen::Isometry3d& T_camera_lidar, int level = 0) const;
  /// Fills depth_agreement and depth_points.
  void depth(const Eigen::Isometry3d& T_camera_lidar, CalibrationCheck::Scores& scores) const;
  /// Fills the plane and outline fields.
  void board(const Eigen::Isometry3d& T_camera_lidar, CalibrationCheck::Scores& scores) const;
  /// [px] mean image motion of the scored edges (those in the image under
  /// A) between transforms A and B.
  double mean_motion(const Eigen::Isometry3d& A_camera_lidar, const Eigen::Isometry3d& B_camera_lidar,
                     bool scene_only = false) const;
  /// [px] Median distance of the scored edges off the board from the
  /// nearest image edge (saturates at 63.75 px); NaN when none is in the image.
  double median_scene_distance(const Eigen::Isometry3d& T_camera_lidar) const;
  /// [m] median camera depth of the scored edges.
  double median_edge_depth(const Eigen::Isometry3d& T_camera_lidar) const;

  int edge_frames() const { return static_cast<int>(edge_frames_.size()); }
  const std::vector<const CheckFrame*>& scored_edge_frames() const { return edge_frames_; }
  int depth_frames() const { return static_cast<int>(depth_frames_.size()); }
  int board_frames() const { return static_cast<int>(board_frames_.size()); }

 private:
  struct PlaneFit {
    double offset = 0.0;  // [m] median height of the lidar board returns over the rims' plane
    double spread = 0.0;  // [m] their robust sigma
    // [m] height of the stereo plane over the rims' plane at the board's centre
    double stereo_offset = std::numeric_limits<double>::quiet_NaN();
    // Their plane against the camera's, as a rotation vector (n_camera x
    // n_lidar, both facing the camera; its length the sine of the tilt).
    // Kept as a vector so that frames average their noise out: the median
    // of per-frame tilt angles would be biased up by it (an angle is never
    // negative), and a board seen by two or three rings tilts by a degree
    // in any one frame.
    Eigen::Vector3d tilt = Eigen::Vector3d::Zero();
  };
  PlaneFit plane_fit(const CheckFrame& frame, const Eigen::Isometry3d& T_camera_lidar) const;

  const std::vector<CheckFrame>& frames_;
  const LeftView& view_;
  const Target& target_;
  const CalibrationCheck::Params& params_;
  std::array<std::array<double, 256>, kLevels> kernels_{};  // edge score of each quantised distance, per level
  std::vector<const CheckFrame*> edge_frames_, depth_frames_, board_frames_;
};

}  // namespace l2s::detail
