// The calibration check (calibration_check.hpp): scores the transform and
// its symmetric alternatives against the whole scene, scans the edge score
// per degree of freedom, and judges.

#include <l2s/calibration_check.hpp>

#include "check/left_view.hpp"
#include "check/edge_alignment.hpp"
#include "check/scene_scorer.hpp"
#include "check/verdict.hpp"

#include <l2s/error.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>

namespace l2s {
namespace {

/// The edge scores of one transform, over the edges it brings into the image.
void score_edges(const detail::EdgeSums& sums, CalibrationCheck::Scores& s) {
  s.edge_points = sums.board_seen + sums.scene_seen;
  s.scene_edge_points = sums.scene_seen;
  s.edge_score = s.edge_points ? (sums.board + sums.scene) / s.edge_points : 0.0;
  s.scene_edge_score = s.scene_edge_points ? sums.scene / s.scene_edge_points : 0.0;
}

/// The scores of one transform. Its support is measured at the best
/// alignment of the edges near it, so that a hypothesis a little off (as any
/// estimate is) is not judged by how far its overlay is off but by whether
/// the scene can be explained by it at all. Its edges count as the share of
/// `most_edges` (the most that any hypothesis brings into the image) that
/// land on image edges: a hypothesis that sends edges out of the image must
/// not win by the few it keeps, and one that brings more in must not score
/// above 1 by their number (as shares of the checked transform's count, a
/// wrong one turning far ground returns up onto a textured image would
/// score about three times the right one). `at_alignment`,
/// when given, receives the scores at that best alignment (with edges).
CalibrationCheck::Scores score(const detail::SceneScorer& scorer, const Eigen::Isometry3d& T_camera_lidar,
                               int most_edges, const detail::LeftView& view, double depth,
                               const CalibrationCheck::Params& params,
                               CalibrationCheck::Scores* at_alignment = nullptr) {
  CalibrationCheck::Scores s;
  score_edges(scorer.edges(T_camera_lidar), s);
  scorer.depth(T_camera_lidar, s);
  scorer.board(T_camera_lidar, s);
  CalibrationCheck::Scores best = s;
  if (s.edge_points > 0) {
    const Eigen::Isometry3d T_best = detail::refine_alignment(scorer, T_camera_lidar, view, depth, params);
    score_edges(scorer.edges(T_best), best);
    scorer.depth(T_best, best);
    scorer.board(T_best, best);
  }
  // Support: the sum of the evidence there is (each 0..1, higher better). A
  // sum, not a mean, so evidence that cannot tell hypotheses apart (the
  // board under a half turn) does not dilute the evidence that can.
  if (best.edge_points > 0) s.support += best.edge_score * best.edge_points / std::max(best.edge_points, most_edges);
  if (std::isfinite(best.depth_agreement)) s.support += best.depth_agreement;
  if (std::isfinite(best.outside_fraction)) s.support += 1.0 - best.outside_fraction;
  if (at_alignment) *at_alignment = best;
  return s;
}

/// Which alternative the scene prefers, and whether it cannot tell.
void compare_hypotheses(CalibrationCheck::Report& report, double margin) {
  double best = report.scores.support + margin;
  for (std::size_t i = 0; i < report.alternatives.size(); ++i) {
    const double support = report.alternatives[i].scores.support;
    if (support > best) best = support, report.preferred = static_cast<int>(i);
    if (std::abs(support - report.scores.support) <= margin) report.ambiguous = true;
  }
  if (report.preferred >= 0) {
    // Preferred only when it stands clear of every other hypothesis too.
    const double preferred = report.alternatives[report.preferred].scores.support;
    for (std::size_t i = 0; i < report.alternatives.size(); ++i)
      if (static_cast<int>(i) != report.preferred && report.alternatives[i].scores.support > preferred - margin)
        report.preferred = -1;
    report.ambiguous = report.preferred < 0;
  }
}

/// [rad] Between the lidar's up (+z) and the image's up (-y) under a
/// transform: 0 for sensors mounted upright, pi for one upside down.
double up_angle(const Eigen::Isometry3d& T_lidar_camera) {
  const Eigen::Vector3d lidar_up = T_lidar_camera.linear().transpose() * Eigen::Vector3d::UnitZ();
  return std::acos(std::clamp(-lidar_up.y(), -1.0, 1.0));
}

}  // namespace

void CalibrationCheck::Params::validate() const {
  const auto positive = [](double value, const char* field) {
    if (!(value > 0.0)) throw ParamError(field, "must be > 0");
  };
  const auto ordered = [](double suspect, double failed, const char* field) {
    if (!(failed >= suspect)) throw ParamError(field, "must be >= its suspect threshold");
  };
  positive(edge_sigma_px, "edge_sigma_px");
  if (max_edge_frames < 1) throw ParamError("max_edge_frames", "must be >= 1");
  positive(scan_range_deg, "scan_range_deg");
  positive(depth_tolerance, "depth_tolerance");
  positive(outline_band, "outline_band");
  positive(suspect_misalignment_deg, "suspect_misalignment_deg");
  ordered(suspect_misalignment_deg, failed_misalignment_deg, "failed_misalignment_deg");
  positive(suspect_roll_deg, "suspect_roll_deg");
  ordered(suspect_roll_deg, failed_roll_deg, "failed_roll_deg");
  positive(suspect_scene_misalignment_deg, "suspect_scene_misalignment_deg");
  ordered(suspect_scene_misalignment_deg, failed_scene_misalignment_deg, "failed_scene_misalignment_deg");
  positive(suspect_outline_deg, "suspect_outline_deg");
  ordered(suspect_outline_deg, failed_outline_deg, "failed_outline_deg");
  positive(suspect_plane_offset, "suspect_plane_offset");
  ordered(suspect_plane_offset, failed_plane_offset, "failed_plane_offset");
  if (!(min_plane_offset_px >= 0.0)) throw ParamError("min_plane_offset_px", "must be >= 0");
  positive(suspect_stereo_offset_px, "suspect_stereo_offset_px");
  ordered(suspect_stereo_offset_px, failed_stereo_offset_px, "failed_stereo_offset_px");
  ordered(suspect_stereo_offset_px, row_texture_stereo_offset_px, "row_texture_stereo_offset_px");
  ordered(row_texture_stereo_offset_px, failed_stereo_offset_px, "failed_stereo_offset_px");
  if (!(row_texture_share >= 0.0 && row_texture_share <= 1.0)) throw ParamError("row_texture_share", "must be in 0..1");
  positive(suspect_plane_tilt_deg, "suspect_plane_tilt_deg");
  ordered(suspect_plane_tilt_deg, failed_plane_tilt_deg, "failed_plane_tilt_deg");
  positive(suspect_pose_scatter_deg, "suspect_pose_scatter_deg");
  ordered(suspect_pose_scatter_deg, failed_pose_scatter_deg, "failed_pose_scatter_deg");
  if (!(suspect_outside_fraction > 0.0 && suspect_outside_fraction < 1.0))
    throw ParamError("suspect_outside_fraction", "must be in (0, 1)");
  ordered(suspect_outside_fraction, failed_outside_fraction, "failed_outside_fraction");
  positive(suspect_center_offset, "suspect_center_offset");
  positive(refuting_center_offset, "refuting_center_offset");
  ordered(suspect_center_offset, failed_center_offset, "failed_center_offset");
  if (!(suspect_alignment_gain > 0.0 && suspect_alignment_gain < 1.0))
    throw ParamError("suspect_alignment_gain", "must be in (0, 1)");
  ordered(suspect_alignment_gain, failed_alignment_gain, "failed_alignment_gain");
  if (!(min_misalignment_gain >= 0.0 && min_misalignment_gain < 1.0))
    throw ParamError("min_misalignment_gain", "must be in [0, 1)");
  if (!(min_optimum_edge_score >= 0.0 && min_optimum_edge_score <= 1.0))
    throw ParamError("min_optimum_edge_score", "must be in [0, 1]");
  if (!(min_misalignment_widths >= 0.0)) throw ParamError("min_misalignment_widths", "must be >= 0");
  if (!(suspect_depth_agreement >= 0.0 && suspect_depth_agreement <= 1.0))
    throw ParamError("suspect_depth_agreement", "must be in [0, 1]");
  if (!(failed_depth_agreement >= 0.0 && failed_depth_agreement <= suspect_depth_agreement))
    throw ParamError("failed_depth_agreement", "must be in [0, suspect_depth_agreement]");
  if (!(min_roll_prominence >= 0.0 && min_roll_prominence <= 1.0))
    throw ParamError("min_roll_prominence", "must be in [0, 1]");
  positive(suspect_depth_tilt_deg, "suspect_depth_tilt_deg");
  ordered(suspect_depth_tilt_deg, failed_depth_tilt_deg, "failed_depth_tilt_deg");
  positive(suspect_depth_bias, "suspect_depth_bias");
  ordered(suspect_depth_bias, failed_depth_bias, "failed_depth_bias");
  if (min_edge_points < 1) throw ParamError("min_edge_points", "must be >= 1");
  if (min_scene_edge_points < 1) throw ParamError("min_scene_edge_points", "must be >= 1");
  if (!(min_prominence >= 0.0 && min_prominence <= 1.0)) throw ParamError("min_prominence", "must be in [0, 1]");
  positive(hypothesis_margin, "hypothesis_margin");
  if (!(upright_deg >= 0.0 && upright_deg <= 45.0)) throw ParamError("upright_deg", "must be in [0, 45]");
}

CalibrationCheck::CalibrationCheck(StereoCamera cameras, Target target)
    : CalibrationCheck(std::move(cameras), target, Params{}) {}

CalibrationCheck::CalibrationCheck(StereoCamera cameras, Target target, Params params)
    : cameras_(std::move(cameras)), target_(target), params_(params) {
  params_.validate();
  target_.validate();
}

CalibrationCheck::Report CalibrationCheck::check(const std::vector<CheckFrame>& frames,
                                                 const Eigen::Isometry3d& T_lidar_camera,
                                                 std::vector<Alternative> alternatives) const {
  const auto start = std::chrono::steady_clock::now();
  Report report;
  report.frames = static_cast<int>(frames.size());
  const detail::LeftView view = detail::LeftView::of(cameras_);
  const detail::SceneScorer scorer(frames, view, target_, params_);
  report.board_frames = scorer.board_frames();
  report.edge_frames = scorer.edge_frames();
  report.depth_frames = scorer.depth_frames();

  const Eigen::Isometry3d T_camera_lidar = T_lidar_camera.inverse();
  report.median_depth = scorer.median_edge_depth(T_camera_lidar);
  const double depth = std::max(report.median_depth, 0.5);
  if (alternatives.empty())
    for (const CheckFrame& frame : frames)
      if (frame.camera.T_camera_board) {
        alternatives = board_alternatives(T_lidar_camera, *frame.camera.T_camera_board, target_);
        break;
      }
  const auto seen = [&](const Eigen::Isometry3d& T) {
    const detail::EdgeSums sums = scorer.edges(T);
    return sums.board_seen + sums.scene_seen;
  };
  int most_seen = seen(T_camera_lidar);
  for (const Alternative& alternative : alternatives)
    most_seen = std::max(most_seen, seen(alternative.T_lidar_camera.inverse()));
  CalibrationCheck::Scores at_alignment;
  report.scores = score(scorer, T_camera_lidar, most_seen, view, depth, params_, &at_alignment);
  for (Alternative& alternative : alternatives)
    alternative.scores = score(scorer, alternative.T_lidar_camera.inverse(), most_seen, view, depth, params_);
  report.up_angle = up_angle(T_lidar_camera);
  for (Alternative& alternative : alternatives) alternative.up_angle = up_angle(alternative.T_lidar_camera);
  report.alternatives = std::move(alternatives);
  compare_hypotheses(report, params_.hypothesis_margin);

  if (report.scores.edge_points > 0) {
    const detail::EdgeAlignment alignment =
        detail::align_edges(scorer, T_camera_lidar, report.scores.edge_points, view, depth, params_);
    report.peaks = alignment.peaks;
    report.misalignment_px = alignment.motion_px;
    report.misalignment = alignment.motion_px / view.fx;
    report.alignment_gain = alignment.gain;
    report.optimum_edge_score = alignment.optimum_score;
    if (alignment.optimum_score > 0.0)
      report.misalignment_gain = std::max(0.0, 1.0 - report.scores.edge_score / alignment.optimum_score);
    // score() measured the board there already: its refine_alignment() is
    // the same optimum as align_edges() finds.
    if (report.board_frames > 0) report.optimum_board = at_alignment;
    if (report.scores.scene_edge_points >= params_.min_scene_edge_points)
      report.scene_misalignment = detail::scene_motion(scorer, T_camera_lidar, view, depth, params_) / view.fx;
  }
  detail::judge(report, params_, view.fx);
  report.milliseconds =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return report;
}

}  // namespace l2s
