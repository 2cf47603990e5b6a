// Scores of one transform (calibration_check.hpp): lidar discontinuities on
// the image's edge distance map (a Gaussian kernel of the distance, as a
// soft count of hits), lidar returns against coarse stereo depth, and the
// lidar board returns in the camera's board frame.

#include "check/scene_scorer.hpp"

#include "plane/plane_fit.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <unordered_map>

namespace l2s::detail {
namespace {

/// Up to `limit` of `all`, evenly spread, in order.
std::vector<const CheckFrame*> spread(const std::vector<const CheckFrame*>& all, int limit) {
  if (static_cast<int>(all.size()) <= limit) return all;
  std::vector<const CheckFrame*> out;
  for (int k = 0; k < limit; ++k) out.push_back(all[(2 * k + 1) * all.size() / (2 * limit)]);
  return out;
}

double median(std::vector<double> values) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  const auto mid = values.begin() + values.size() / 2;
  std::nth_element(values.begin(), mid, values.end());
  return *mid;
}

/// [m] Distance of a board-frame point from the nearest contour of the
/// board (outline or a hole rim), in its plane.
double contour_distance(const Eigen::Vector2d& q, const Target& target) {
  const double dx = std::abs(q.x()) - target.board_width / 2, dy = std::abs(q.y()) - target.board_height / 2;
  double d = (dx > 0 || dy > 0) ? Eigen::Vector2d(std::max(dx, 0.0), std::max(dy, 0.0)).norm() : -std::max(dx, dy);
  for (const auto& c : target.hole_centers()) d = std::min(d, std::abs((q - c).norm() - target.hole_radius));
  return d;
}

/// True when a board-frame point is off the board: beyond the outline or
/// inside a hole by more than `band` [m].
bool off_board(const Eigen::Vector2d& q, const Target& target, double band) {
  if (std::abs(q.x()) > target.board_width / 2 + band || std::abs(q.y()) > target.board_height / 2 + band) return true;
  for (const auto& c : target.hole_centers())
    if ((q - c).norm() < target.hole_radius - band) return true;
  return false;
}

struct VisibleReturn {
  Eigen::Vector3d p_lidar;
  double u, v;   // [px]
  double depth;  // [m] rectified frame
};

/// True when the camera sees the board in front of `p_camera`: its ray
/// crosses the board's face (outside the holes) before reaching it. The
/// lidar sees the wall through the holes and past the edges from elsewhere.
bool behind_board(const Eigen::Vector3d& p_camera, const Eigen::Isometry3d& T_camera_board, const Target& target) {
  const Eigen::Vector3d n = T_camera_board.linear().col(2), o = T_camera_board.translation();
  const double along = n.dot(p_camera);
  if (std::abs(along) < 1e-9) return false;
  const double t = n.dot(o) / along;  // the ray p(t) = t * p_camera meets the plane at t
  constexpr double kBehind = 0.05;    // [m] board returns (on the plane, with noise) stay visible
  if (!(t > 0.0 && (1.0 - t) * p_camera.norm() > kBehind)) return false;
  const Eigen::Vector2d q = (T_camera_board.inverse() * (t * p_camera)).head<2>();
  return !off_board(q, target, 0.0);
}

/// The returns the camera can see: each projects into the image and is not
/// hidden behind a nearer return of its cell (a z-buffer on cells of
/// kCell px). Lidar and camera look from different places, so the lidar
/// sees surfaces the camera does not (through the holes, behind the board's
/// edges); compared with stereo they would count against a right transform.
std::vector<VisibleReturn> visible_returns(const LidarProjector& projector, const std::vector<Eigen::Vector3d>& points) {
  constexpr double kCell = 16.0;  // [px] about the spacing of returns along a ring at the board
  std::vector<VisibleReturn> seen;
  double u, v;
  for (const auto& p : points)
    if (projector.project(p, u, v) && projector.inside(u, v)) seen.push_back({p, u, v, projector.depth(p)});
  std::unordered_map<long, double> nearest;
  const auto cell = [&](const VisibleReturn& r) {
    return (static_cast<long>(r.v / kCell) << 20) + static_cast<long>(r.u / kCell);
  };
  for (const auto& r : seen) {
    const auto [it, added] = nearest.emplace(cell(r), r.depth);
    if (!added) it->second = std::min(it->second, r.depth);
  }
  std::vector<VisibleReturn> out;
  for (const auto& r : seen)
    if (r.depth <= 1.05 * nearest[cell(r)] + 0.1) out.push_back(r);
  return out;
}

}  // namespace

SceneScorer::SceneScorer(const std::vector<CheckFrame>& frames, const LeftView& view, const Target& target,
                         const CalibrationCheck::Params& params)
    : frames_(frames), view_(view), target_(target), params_(params) {
  for (int level = 0; level < kLevels; ++level)
    for (std::size_t q = 0; q < 256; ++q) {
      const double d = q * EdgeDistanceMap{}.unit / (params.edge_sigma_px * (1 << level));
      kernels_[level][q] = q == 255 ? 0.0 : std::exp(-0.5 * d * d);
    }
  std::vector<const CheckFrame*> with_edges, with_depth;
  for (const CheckFrame& frame : frames) {
    const bool sized = frame.camera.edges.width == view.width && frame.camera.edges.height == view.height;
    if (!frame.camera.edges.empty() && sized) with_edges.push_back(&frame);
    if (!frame.camera.depth.empty() && !frame.lidar.scene.empty()) with_depth.push_back(&frame);
    if (frame.camera.T_camera_board && frame.lidar.board.size() >= 3) board_frames_.push_back(&frame);
  }
  edge_frames_ = spread(with_edges, params.max_edge_frames);
  depth_frames_ = spread(with_depth, params.max_edge_frames);
}

EdgeSums SceneScorer::edges(const Eigen::Isometry3d& T_camera_lidar, int level) const {
  const LidarProjector projector(view_, T_camera_lidar);
  const std::array<double, 256>& kernel = kernels_[level];
  EdgeSums sums;
  double u, v;
  for (const CheckFrame* frame : edge_frames_) {
    const EdgeDistanceMap& map = frame->camera.edges;
    const auto score = [&](const std::vector<Eigen::Vector3d>& edges, double& sum, int& seen) {
      for (const auto& e : edges) {
        if (!projector.project(e, u, v) || !projector.inside(u, v)) continue;
        const long x = std::lround(u), y = std::lround(v);
        sum += kernel[map.distance[static_cast<std::size_t>(y) * map.width + x]];
        ++seen;
      }
    };
    score(frame->lidar.board_edges, sums.board, sums.board_seen);
    score(frame->lidar.scene_edges, sums.scene, sums.scene_seen);
  }
  return sums;
}

void SceneScorer::depth(const Eigen::Isometry3d& T_camera_lidar, CalibrationCheck::Scores& scores) const {
  const LidarProjector projector(view_, T_camera_lidar);
  int agree = 0, compared = 0;
  for (const CheckFrame* frame : depth_frames_) {
    const DepthMap& map = frame->camera.depth;
    for (const VisibleReturn& r : visible_returns(projector, frame->lidar.scene)) {
      if (frame->camera.T_camera_board && behind_board(T_camera_lidar * r.p_lidar, *frame->camera.T_camera_board, target_))
        continue;
      const double stereo = map.at(r.u, r.v);
      if (!std::isfinite(stereo)) continue;
      const double sigma = map.depth_noise * stereo * stereo;
      ++compared;
      agree += std::abs(r.depth - stereo) <= params_.depth_tolerance * stereo + 3.0 * sigma;
    }
  }
  scores.depth_points = compared;
  scores.depth_agreement = compared > 0 ? static_cast<double>(agree) / compared : CalibrationCheck::Scores::kNaN;
}

void SceneScorer::board(const Eigen::Isometry3d& T_camera_lidar, CalibrationCheck::Scores& scores) const {
  std::vector<double> offsets, spreads, tilts, outline_px;
  std::size_t outside = 0, returns = 0;
  for (const CheckFrame* frame : board_frames_) {
    const Eigen::Isometry3d T_board_lidar = frame->camera.T_camera_board->inverse() * T_camera_lidar;
    std::vector<Eigen::Vector3d> in_board;
    std::vector<double> heights;
    for (const auto& p : frame->lidar.board) {
      const Eigen::Vector3d q = T_board_lidar * p;
      in_board.push_back(q);
      heights.push_back(q.z());
      outside += off_board(q.head<2>(), target_, params_.outline_band);
    }
    returns += in_board.size();
    const double offset = median(heights);
    std::vector<double> deviations;
    for (const double h : heights) deviations.push_back(std::abs(h - offset));
    offsets.push_back(offset);
    spreads.push_back(1.4826 * median(deviations));
    std::vector<std::size_t> all(in_board.size());
    std::iota(all.begin(), all.end(), 0);
    tilts.push_back(std::acos(std::min(1.0, std::abs(fit_plane(in_board, all).normal().z()))));
    for (const auto& e : frame->lidar.board_edges) {
      const Eigen::Vector3d q = T_board_lidar * e;
      const double depth = (T_camera_lidar * e).z();
      if (depth > 0.1) outline_px.push_back(contour_distance(q.head<2>(), target_) * view_.fx / depth);
    }
  }
  if (board_frames_.empty()) return;
  scores.plane_offset = median(offsets);
  scores.plane_spread = median(spreads);
  scores.plane_tilt = median(tilts);
  scores.outline_px = median(outline_px);
  scores.outside_fraction = returns ? static_cast<double>(outside) / returns : CalibrationCheck::Scores::kNaN;
}

double SceneScorer::mean_motion(const Eigen::Isometry3d& A_camera_lidar,
                                const Eigen::Isometry3d& B_camera_lidar) const {
  const LidarProjector a(view_, A_camera_lidar), b(view_, B_camera_lidar);
  double sum = 0.0, ua, va, ub, vb;
  int n = 0;
  for (const CheckFrame* frame : edge_frames_)
    for (const auto* edges : {&frame->lidar.board_edges, &frame->lidar.scene_edges})
      for (const auto& e : *edges)
        if (a.project(e, ua, va) && a.inside(ua, va) && b.project(e, ub, vb)) sum += std::hypot(ub - ua, vb - va), ++n;
  return n ? sum / n : 0.0;
}

double SceneScorer::median_edge_depth(const Eigen::Isometry3d& T_camera_lidar) const {
  const LidarProjector projector(view_, T_camera_lidar);
  std::vector<double> depths;
  double u, v;
  for (const CheckFrame* frame : edge_frames_)
    for (const auto* edges : {&frame->lidar.board_edges, &frame->lidar.scene_edges})
      for (const auto& e : *edges)
        if (projector.project(e, u, v) && projector.inside(u, v)) depths.push_back(projector.depth(e));
  return depths.empty() ? 0.0 : median(depths);
}

}  // namespace l2s::detail
