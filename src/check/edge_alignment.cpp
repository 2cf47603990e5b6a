// Edge alignment around a transform (calibration_check.hpp).
//
// The best alignment near the checked transform is found in all six degrees
// of freedom at once, as chamfer matching: every projected lidar edge is
// pulled towards its nearest image edge along the gradient of the image's
// edge distance map, and Gauss-Newton with Cauchy weights (their scale
// shrinking from 8 kernel sigmas to one, so tens of pixels are reached and
// far mismatches stop counting) and Levenberg damping (weakly observed
// degrees of freedom stay put) solves for the motion. What a user sees of a
// misalignment is how far the overlay moves to reach that optimum (the mean
// image motion of the edges), which does not depend on how coupled degrees
// of freedom (a turn and a shift) share it. One-dimensional scans of the
// kernel score around the optimum then give the peak widths (how firmly the
// scene holds each degree of freedom) and any better alignment farther away.

#include "check/edge_alignment.hpp"

#include "check/peak_scan.hpp"

#include <algorithm>
#include <cmath>

namespace l2s::detail {
namespace {

constexpr double kDeg = M_PI / 180.0;
using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

/// T_camera_lidar moved by a twist of the camera frame: rotation vector
/// (about the camera centre), then translation.
Eigen::Isometry3d moved_by(const Vector6d& twist, const Eigen::Isometry3d& T_camera_lidar) {
  Eigen::Isometry3d E = Eigen::Isometry3d::Identity();
  const Eigen::Vector3d r = twist.head<3>();
  if (r.norm() > 0.0) E.linear() = Eigen::AngleAxisd(r.norm(), r.normalized()).toRotationMatrix();
  E.translation() = twist.tail<3>();
  return E * T_camera_lidar;
}

/// [px] Bilinear edge distance at (u, v) and its gradient; false near the border.
bool distance_and_gradient(const EdgeDistanceMap& map, double u, double v, double& d, Eigen::Vector2d& g) {
  const int x = static_cast<int>(std::floor(u)), y = static_cast<int>(std::floor(v));
  if (x < 1 || y < 1 || x + 2 >= map.width || y + 2 >= map.height) return false;
  const auto D = [&](int xx, int yy) { return map.unit * map.distance[static_cast<std::size_t>(yy) * map.width + xx]; };
  const double fx = u - x, fy = v - y;
  const auto bilinear = [&](int xx, int yy) {
    return (1 - fx) * (1 - fy) * D(xx, yy) + fx * (1 - fy) * D(xx + 1, yy) + (1 - fx) * fy * D(xx, yy + 1) +
           fx * fy * D(xx + 1, yy + 1);
  };
  d = bilinear(x, y);
  g = 0.5 * Eigen::Vector2d(bilinear(x + 1, y) - bilinear(x - 1, y), bilinear(x, y + 1) - bilinear(x, y - 1));
  return true;
}

/// d(u, v) / d(twist) of a lidar point at p_camera.
Eigen::Matrix<double, 2, 6> projection_jacobian(const LeftView& view, const Eigen::Vector3d& p_camera) {
  const Eigen::Vector3d p = view.R_rect_camera * p_camera;
  const Eigen::Vector4d h(p.x(), p.y(), p.z(), 1.0);
  const double a = view.P.row(0) * h, b = view.P.row(1) * h, w = view.P.row(2) * h;
  Eigen::Matrix<double, 2, 3> d_rect;
  d_rect.row(0) = (view.P.block<1, 3>(0, 0) * w - a * view.P.block<1, 3>(2, 0)) / (w * w);
  d_rect.row(1) = (view.P.block<1, 3>(1, 0) * w - b * view.P.block<1, 3>(2, 0)) / (w * w);
  Eigen::Matrix<double, 3, 6> d_camera;
  d_camera << 0.0, p_camera.z(), -p_camera.y(), 1.0, 0.0, 0.0,  //
      -p_camera.z(), 0.0, p_camera.x(), 0.0, 1.0, 0.0,          //
      p_camera.y(), -p_camera.x(), 0.0, 0.0, 0.0, 1.0;
  return d_rect * view.R_rect_camera * d_camera;
}

/// One damped Gauss-Newton step of the Cauchy-weighted chamfer cost (of
/// the edges off the board alone when `scene_only`).
Vector6d chamfer_step(const SceneScorer& scorer, const LeftView& view, const Eigen::Isometry3d& T_camera_lidar,
                      double scale, bool scene_only, const Vector6d& mask) {
  Matrix6d H = Matrix6d::Zero();
  Vector6d g = Vector6d::Zero();
  const LidarProjector projector(view, T_camera_lidar);
  for (const CheckFrame* frame : scorer.scored_edge_frames())
    for (const auto* edges : {&frame->lidar.board_edges, &frame->lidar.scene_edges})
      for (const auto& e : *edges) {
        if (scene_only && edges != &frame->lidar.scene_edges) break;
        double u, v, d;
        Eigen::Vector2d gradient;
        if (!projector.project(e, u, v) || !distance_and_gradient(frame->camera.edges, u, v, d, gradient)) continue;
        const Eigen::Matrix<double, 1, 6> J = gradient.transpose() * projection_jacobian(view, T_camera_lidar * e);
        const double w = 1.0 / (1.0 + (d / scale) * (d / scale));
        H += w * J.transpose() * J;
        g += w * J.transpose() * d;
      }
  H.diagonal() += 0.1 * H.diagonal() + Vector6d::Constant(1e-9);
  // Degrees of freedom left out stay put: their rows and columns decouple.
  for (int k = 0; k < 6; ++k)
    if (mask[k] == 0.0) H.row(k).setZero(), H.col(k).setZero(), H(k, k) = 1.0, g[k] = 0.0;
  return -H.ldlt().solve(g);
}

/// Steps of about one kernel sigma of image motion per degree of freedom
/// (at the image centre for rx and ry, a quarter width off it for the roll
/// rz, at the edges' median depth for translations) and how far scans reach.
struct Steps {
  Vector6d step, reach;
  Steps(const LeftView& view, double depth, const CalibrationCheck::Params& p) {
    const double angle = p.edge_sigma_px / view.fx, range = p.scan_range_deg * kDeg;
    step << angle, angle, 4.0 * p.edge_sigma_px / view.width, angle * depth, angle * depth, angle * depth;
    reach << range, range, 2.0 * range, range * depth, range * depth, range * depth;
  }
};

/// The twist that moves T_camera_lidar to the best alignment near it.
Vector6d chamfer_optimum(const SceneScorer& scorer, const Eigen::Isometry3d& T_camera_lidar, const LeftView& view,
                         double depth, const CalibrationCheck::Params& params, bool scene_only = false) {
  // The edges off the board are few (a box or a post, the same in every
  // frame of a static scene): they can fix an image shift (rx, ry), not six
  // degrees of freedom.
  Vector6d mask = Vector6d::Ones();
  if (scene_only) mask << 1, 1, 0, 0, 0, 0;
  // Coarse to fine: the Cauchy scale shrinks from 8 sigmas to one.
  Vector6d optimum = Vector6d::Zero();
  for (double scale = 8.0; scale >= 1.0; scale *= 0.5)
    for (int iteration = 0; iteration < 4; ++iteration) {
      const Vector6d step =
          chamfer_step(scorer, view, moved_by(optimum, T_camera_lidar), scale * params.edge_sigma_px, scene_only, mask);
      optimum += step;  // small steps compose additively well enough
      if (step.head<3>().norm() * view.fx < 0.01 && step.tail<3>().norm() * view.fx / depth < 0.01) break;
    }
  // Keep the optimum only where it scores at least as well as the start (the
  // damping on a flat score must not count as motion).
  const auto score = [&](const Eigen::Isometry3d& T) {
    const EdgeSums sums = scorer.edges(T);
    return scene_only ? sums.scene : sums.board + sums.scene;
  };
  if (score(moved_by(optimum, T_camera_lidar)) < score(T_camera_lidar)) optimum.setZero();
  return optimum;
}

}  // namespace

Eigen::Isometry3d refine_alignment(const SceneScorer& scorer, const Eigen::Isometry3d& T_camera_lidar,
                                   const LeftView& view, double depth, const CalibrationCheck::Params& params) {
  return moved_by(chamfer_optimum(scorer, T_camera_lidar, view, depth, params), T_camera_lidar);
}

double scene_motion(const SceneScorer& scorer, const Eigen::Isometry3d& T_camera_lidar, const LeftView& view,
                    double depth, const CalibrationCheck::Params& params) {
  // Measured as how much closer to image edges the shift brings them (their
  // median distance), not as how far they move: a shift along an edge (a
  // post's vertical side) is free and says nothing.
  const Eigen::Isometry3d T_all = refine_alignment(scorer, T_camera_lidar, view, depth, params);
  const Vector6d optimum = chamfer_optimum(scorer, T_all, view, depth, params, true);
  const double gained = scorer.median_scene_distance(T_all) - scorer.median_scene_distance(moved_by(optimum, T_all));
  return std::isfinite(gained) ? std::max(0.0, gained) : 0.0;
}

EdgeAlignment align_edges(const SceneScorer& scorer, const Eigen::Isometry3d& T_camera_lidar, int edge_points,
                          const LeftView& view, double depth, const CalibrationCheck::Params& params) {
  static const char* kNames[6] = {"rx", "ry", "rz", "tx", "ty", "tz"};
  const auto score = [&](const Eigen::Isometry3d& T) {
    const EdgeSums sums = scorer.edges(T);
    return (sums.board + sums.scene) / std::max(1, edge_points);
  };
  const Vector6d optimum = chamfer_optimum(scorer, T_camera_lidar, view, depth, params);
  EdgeAlignment out;
  out.T_camera_lidar_best = moved_by(optimum, T_camera_lidar);
  out.motion_px = scorer.mean_motion(T_camera_lidar, out.T_camera_lidar_best);
  const double at_optimum = score(out.T_camera_lidar_best);
  out.optimum_score = at_optimum;
  const Steps steps(view, depth, params);
  for (int k = 0; k < 6; ++k) {
    const auto along = [&](double amount) {
      Vector6d a = optimum;
      a[k] += amount;
      return score(moved_by(a, T_camera_lidar));
    };
    const ScanPeak peak = scan_peak(along, steps.step[k], steps.reach[k]);
    const double gain = peak.best_value > 0.0 ? std::max(0.0, 1.0 - at_optimum / peak.best_value) : 0.0;
    out.peaks[k] = {kNames[k], k < 3, optimum[k] + peak.offset, peak.width, peak.prominence,
                    optimum[k] + peak.best_offset, gain};
    out.gain = std::max(out.gain, gain);
  }
  return out;
}

}  // namespace l2s::detail
