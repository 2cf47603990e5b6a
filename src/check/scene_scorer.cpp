// Scores of one transform (calibration_check.hpp): lidar discontinuities on
// the image's edge distance map (a Gaussian kernel of the distance, as a
// soft count of hits) and the lidar board returns in the camera's board
// frame. The depth scores are in scene_depth.cpp.

#include "check/scene_scorer.hpp"

#include "check/board_geometry.hpp"
#include "plane/plane_fit.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace l2s::detail {
namespace {

/// Up to `limit` of `all`, evenly spread, in order.
std::vector<const CheckFrame*> spread(const std::vector<const CheckFrame*>& all, int limit) {
  if (static_cast<int>(all.size()) <= limit) return all;
  std::vector<const CheckFrame*> out;
  for (int k = 0; k < limit; ++k) out.push_back(all[(2 * k + 1) * all.size() / (2 * limit)]);
  return out;
}

/// Up to `limit` of `all`, the frames with the board on both sides first
/// (they hold the richest evidence; a ring-free lidar's is its accumulated
/// window, where the others hold a sparse sweep each), the rest evenly spread.
std::vector<const CheckFrame*> boards_first(const std::vector<const CheckFrame*>& all, int limit) {
  std::vector<const CheckFrame*> boards, others;
  for (const CheckFrame* frame : all)
    (frame->camera.T_camera_board && !frame->lidar.board.empty() ? boards : others).push_back(frame);
  std::vector<const CheckFrame*> out = spread(boards, limit);
  for (const CheckFrame* frame : spread(others, limit - static_cast<int>(out.size()))) out.push_back(frame);
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
  // The board is measured against the rims' pose: where some frames have it,
  // the others' stereo circle poses (their rim refinement failed; millimetres
  // off, tilted by degrees) would judge a transform by a board that the fit
  // itself left out (pose_registration.cpp). A right result of random scene
  // 1653306487 (2.8 mm, 0.10 deg) was `failed` on them: board 33 mm, 6.4 deg.
  const auto refined = [](const CheckFrame* f) { return f->camera.board_pose_refined; };
  if (std::any_of(board_frames_.begin(), board_frames_.end(), refined))
    board_frames_.erase(std::remove_if(board_frames_.begin(), board_frames_.end(),
                                       [&](const CheckFrame* f) { return !refined(f); }),
                        board_frames_.end());
  edge_frames_ = boards_first(with_edges, params.max_edge_frames);
  depth_frames_ = boards_first(with_depth, params.max_edge_frames);
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

void SceneScorer::board(const Eigen::Isometry3d& T_camera_lidar, CalibrationCheck::Scores& scores) const {
  std::vector<double> offsets, offsets_px, stereo_offsets, stereo_offsets_px, row_textures, spreads, outline_px,
      center_x, center_y;
  std::array<std::vector<double>, 3> tilts;
  std::size_t outside = 0, returns = 0;
  const auto holes = target_.hole_centers();
  for (const CheckFrame* frame : board_frames_) {
    const PlaneFit fit = plane_fit(*frame, T_camera_lidar);
    offsets.push_back(fit.offset);
    // The board's depth, which sets the disparity a plane offset amounts to.
    const double depth = frame->camera.T_camera_board->translation().z();
    const double px_per_m =
        view_.fx_baseline > 0.0 && depth > 0.1 ? view_.fx_baseline / (depth * depth) : CalibrationCheck::Scores::kNaN;
    if (std::isfinite(px_per_m)) offsets_px.push_back(fit.offset * px_per_m);
    if (std::isfinite(frame->camera.stereo_row_texture)) row_textures.push_back(frame->camera.stereo_row_texture);
    if (std::isfinite(fit.stereo_offset)) {
      stereo_offsets.push_back(fit.stereo_offset);
      if (std::isfinite(px_per_m)) stereo_offsets_px.push_back(fit.stereo_offset * px_per_m);
    }
    spreads.push_back(fit.spread);
    for (int k = 0; k < 3; ++k) tilts[k].push_back(fit.tilt[k]);
    const Eigen::Isometry3d T_board_lidar = frame->camera.T_camera_board->inverse() * T_camera_lidar;
    for (const auto& p : frame->lidar.board)
      outside += off_board((T_board_lidar * p).head<2>(), target_, params_.outline_band);
    returns += frame->lidar.board.size();
    for (const auto& c : frame->lidar.hole_centers) {
      const Eigen::Vector2d q = (T_board_lidar * c).head<2>();
      Eigen::Vector2d nearest = holes[0];
      for (const auto& h : holes)
        if ((q - h).norm() < (q - nearest).norm()) nearest = h;
      center_x.push_back(q.x() - nearest.x());
      center_y.push_back(q.y() - nearest.y());
    }
    // A single sweep of a ring-free lidar is too sparse for its grid
    // discontinuities on the board to trace the outline and rims: the
    // empty cells between its petals are edges too. Its board returns,
    // plane and centres still count.
    if (!frame->lidar.ring_free)
      for (const auto& e : frame->lidar.board_edges) {
        const double depth = (T_camera_lidar * e).z();
        if (depth > 0.1)
          outline_px.push_back(contour_distance((T_board_lidar * e).head<2>(), target_) * view_.fx / depth);
      }
  }
  if (board_frames_.empty()) return;
  scores.plane_offset = median(offsets);
  if (!offsets_px.empty()) scores.plane_offset_px = median(offsets_px);
  if (!stereo_offsets.empty()) scores.stereo_offset = median(stereo_offsets);
  if (!stereo_offsets_px.empty()) scores.stereo_offset_px = median(stereo_offsets_px);
  if (!row_textures.empty()) scores.stereo_row_texture = median(row_textures);
  scores.plane_spread = median(spreads);
  const Eigen::Vector3d tilt(median(tilts[0]), median(tilts[1]), median(tilts[2]));
  scores.plane_tilt = std::asin(std::min(1.0, tilt.norm()));
  if (board_frames_.size() >= 3) {
    const Eigen::Vector3d scatter(robust_sigma(tilts[0], tilt[0]), robust_sigma(tilts[1], tilt[1]),
                                  robust_sigma(tilts[2], tilt[2]));
    scores.pose_scatter = std::asin(std::min(1.0, scatter.norm()));
  }
  scores.outline_px = median(outline_px);
  scores.outside_fraction = returns ? static_cast<double>(outside) / returns : CalibrationCheck::Scores::kNaN;
  if (!center_x.empty()) scores.center_offset = std::hypot(median(center_x), median(center_y));
}

SceneScorer::PlaneFit SceneScorer::plane_fit(const CheckFrame& frame, const Eigen::Isometry3d& T_camera_lidar) const {
  // The plane of the pose the rims give in both images: placed to a few
  // hundredths of a pixel of disparity and tilted by tenths of a degree at
  // most. Stereo points of the board are not as good a reference: a face
  // without texture across the rows is matched by smoothness from its
  // edges (wood grain along the rows: 1-2 px off), and matches fattened over
  // its edges and into its holes tilt their plane by degrees. The stereo
  // plane is compared with the rims' instead: a wrong target size scales
  // the rims' depth but not the stereo's.
  const Eigen::Isometry3d& T_camera_board = *frame.camera.T_camera_board;
  const Plane plane = facing_origin(Plane(T_camera_board.linear().col(2), T_camera_board.translation()));
  PlaneFit fit;
  if (frame.camera.stereo_plane)
    fit.stereo_offset = -facing_origin(*frame.camera.stereo_plane).signedDistance(T_camera_board.translation());
  std::vector<Eigen::Vector3d> in_camera;
  std::vector<double> heights;
  for (const auto& p : frame.lidar.board) {
    in_camera.push_back(T_camera_lidar * p);
    heights.push_back(plane.signedDistance(in_camera.back()));
  }
  fit.offset = median(heights);
  fit.spread = robust_sigma(heights, fit.offset);
  std::vector<std::size_t> all(in_camera.size());
  std::iota(all.begin(), all.end(), 0);
  Eigen::Vector3d n_lidar = fit_plane(in_camera, all).normal();
  const Eigen::Vector3d n_camera = plane.normal();
  if (n_lidar.dot(n_camera) < 0.0) n_lidar = -n_lidar;
  fit.tilt = n_camera.cross(n_lidar);
  return fit;
}

double SceneScorer::mean_motion(const Eigen::Isometry3d& A_camera_lidar, const Eigen::Isometry3d& B_camera_lidar,
                                bool scene_only) const {
  const LidarProjector a(view_, A_camera_lidar), b(view_, B_camera_lidar);
  double sum = 0.0, ua, va, ub, vb;
  int n = 0;
  for (const CheckFrame* frame : edge_frames_)
    for (const auto* edges : {&frame->lidar.board_edges, &frame->lidar.scene_edges})
      for (const auto& e : *edges)
        if (!scene_only || edges == &frame->lidar.scene_edges)
        if (a.project(e, ua, va) && a.inside(ua, va) && b.project(e, ub, vb)) sum += std::hypot(ub - ua, vb - va), ++n;
  return n ? sum / n : 0.0;
}

double SceneScorer::median_scene_distance(const Eigen::Isometry3d& T_camera_lidar) const {
  const LidarProjector projector(view_, T_camera_lidar);
  std::vector<double> distances;
  double u, v;
  for (const CheckFrame* frame : edge_frames_)
    for (const auto& e : frame->lidar.scene_edges)
      if (projector.project(e, u, v) && projector.inside(u, v)) distances.push_back(frame->camera.edges.at(u, v));
  return median(distances);
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
