#pragma once
// How well and how firmly the lidar edges align with the image around a
// transform (private to the library).

#include "check/left_view.hpp"
#include "check/scene_scorer.hpp"

#include <l2s/calibration_check.hpp>

#include <array>

namespace l2s::detail {

struct EdgeAlignment {
  Eigen::Isometry3d T_camera_lidar_best = Eigen::Isometry3d::Identity();  ///< the local optimum near the checked transform
  std::array<CalibrationCheck::DofPeak, 6> peaks;  ///< offsets of that optimum; widths and side lobes of scans around it
  double motion_px = 0.0;  ///< [px] mean image motion of the edges from the checked transform to the optimum
  double gain = 0.0;       ///< 1 - optimum's score / best score of any scan around it
  double optimum_score = 0.0;  ///< edge score at the optimum
};

/// The best alignment of the lidar edges with the image edges near
/// T_camera_lidar (all six degrees of freedom); T_camera_lidar itself when
/// there is none better. `depth` [m]: the edges' median depth.
Eigen::Isometry3d refine_alignment(const SceneScorer& scorer, const Eigen::Isometry3d& T_camera_lidar,
                                   const LeftView& view, double depth, const CalibrationCheck::Params& params);

/// [px] How much nearer to image edges (median distance) the edges off the
/// board come when shifted on their own (rotation about the camera's x and
/// y) from the best alignment of all edges.
double scene_motion(const SceneScorer& scorer, const Eigen::Isometry3d& T_camera_lidar, const LeftView& view,
                    double depth, const CalibrationCheck::Params& params);

/// refine_alignment, then scans of each degree of freedom around the
/// optimum. `edge_points` normalises the score.
EdgeAlignment align_edges(const SceneScorer& scorer, const Eigen::Isometry3d& T_camera_lidar, int edge_points,
                          const LeftView& view, double depth, const CalibrationCheck::Params& params);

}  // namespace l2s::detail
