// The verdict rules of the calibration check. Each measurement has a
// suspect and a failed threshold (CalibrationCheck::Params); the verdict is
// the worst level reached, and every rule reached leaves a reason.

#include "check/verdict.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

namespace l2s::detail {
namespace {

using Verdict = CalibrationCheck::Verdict;

constexpr double kDeg = M_PI / 180.0;

struct Judgement {
  std::vector<std::string> failed, suspect;

  /// Adds `text` at the level `value` reaches (NaN: no evidence, no reason).
  void grade(double value, double suspect_at, double failed_at, const std::string& text) {
    if (!(std::abs(value) > suspect_at)) return;
    (std::abs(value) > failed_at ? failed : suspect).push_back(text);
  }
};

std::string format(const char* pattern, double a, double b = 0.0, double c = 0.0) {
  char text[256];
  std::snprintf(text, sizeof text, pattern, a, b, c);
  return text;
}

void judge_board(const CalibrationCheck::Report& r, const CalibrationCheck::Params& p, double fx, Judgement& j) {
  const auto& s = r.scores;
  if (!(std::abs(s.plane_offset_px) < p.min_plane_offset_px))  // NaN: no depth scale, grade as it stands
    j.grade(s.plane_offset, p.suspect_plane_offset, p.failed_plane_offset,
            format("lidar board returns lie %.1f mm (%.2f px of disparity) from the camera's board plane",
                   s.plane_offset * 1e3, s.plane_offset_px));
  // On a face textured along the rows SGBM fills the board in from its
  // surroundings: it measures the board too poorly to fail a result by
  // itself (wood grain along the rows puts the stereo plane a few px of
  // disparity before the rims' on a board whose result is millimetres
  // right). A wrong target size or baseline also shifts the lidar depths
  // against the stereo's off the board.
  const bool row_texture = s.stereo_row_texture >= p.row_texture_share;
  j.grade(s.stereo_offset_px, row_texture ? p.row_texture_stereo_offset_px : p.suspect_stereo_offset_px,
          row_texture ? std::numeric_limits<double>::infinity() : p.failed_stereo_offset_px,
          format("the camera's stereo places the board %.1f mm (%.2f px of disparity) from where its hole rims do "
                 "(a target.yaml of another size than the board, or a wrong baseline)",
                 s.stereo_offset * 1e3, s.stereo_offset_px));
  j.grade(s.plane_tilt, p.suspect_plane_tilt_deg * kDeg, p.failed_plane_tilt_deg * kDeg,
          format("the lidar board is tilted %.2f deg against the camera's", s.plane_tilt / kDeg));
  j.grade(s.pose_scatter, p.suspect_pose_scatter_deg * kDeg, p.failed_pose_scatter_deg * kDeg,
          format("the camera's board pose turns by %.2f deg from frame to frame (its detection is unstable in this "
                 "scene; the result may carry its error, which the board agreeing with the lidar cannot show)",
                 s.pose_scatter / kDeg));
  j.grade(s.outline_px / fx, p.suspect_outline_deg * kDeg, p.failed_outline_deg * kDeg,
          format("lidar board edges lie %.1f px (%.2f deg) from the board's outline and hole rims", s.outline_px,
                 s.outline_px / fx / kDeg));
  // Graded by its lower bound: coarse stereo with few returns off the board
  // tilts a good result by up to twice its frame-to-frame spread.
  const double tilt_sigma = std::isfinite(s.depth_tilt_sigma) ? s.depth_tilt_sigma : 0.0;
  j.grade(std::max(0.0, s.depth_tilt - 2.0 * tilt_sigma), p.suspect_depth_tilt_deg * kDeg, p.failed_depth_tilt_deg * kDeg,
          format("off the board, lidar depths tilt %.2f +- %.2f deg against the stereo depths (a rotation error; the "
                 "board may have moved between the lidar sweep and the images)",
                 s.depth_tilt / kDeg, tilt_sigma / kDeg));
  if (s.depth_points >= 100)  // fewer: too little to judge by
    j.grade(1.0 - s.depth_agreement, 1.0 - p.suspect_depth_agreement, 1.0 - p.failed_depth_agreement,
            format("only %.0f %% of the lidar returns agree with the stereo depth at their pixels (a right "
                   "transform has most agree)",
                   100.0 * s.depth_agreement));
  j.grade(s.depth_bias, p.suspect_depth_bias, p.failed_depth_bias,
          format("lidar depths are %+.1f %% off the stereo depths (a wrong target size or baseline, or a shift along "
                 "the view)",
                 100.0 * s.depth_bias));
  j.grade(s.center_offset, p.suspect_center_offset, p.failed_center_offset,
          format("the lidar's hole centres lie %.1f mm from the camera's holes in the board plane (a shift or turn of "
                 "the transform)",
                 s.center_offset * 1e3));
  j.grade(s.outside_fraction, p.suspect_outside_fraction, p.failed_outside_fraction,
          format("%.0f %% of the lidar board returns fall outside the board's outline or inside a hole "
                 "(wrong transform, or a target.yaml that is not the board)",
                 100.0 * s.outside_fraction));
}

/// Does the best alignment near the transform lie beyond `widths` half
/// widths of the score's peak along some degree of freedom? A peak without a
/// measured width counts as narrow.
bool beyond_its_peak(const std::array<CalibrationCheck::DofPeak, 6>& peaks, double widths) {
  for (const auto& peak : peaks)
    if (!(std::abs(peak.offset) <= widths * peak.width) || peak.width <= 0.0) return true;
  return false;
}

/// Does the board refute the edges' best alignment, with nothing else for
/// it (CalibrationCheck::Params::refuting_center_offset)? Its hole centres,
/// outline and plane are measured against the camera's board pose, not
/// against image edges: the centres lie far off each other there and not
/// here, or an outline or plane measure is within half its suspect level
/// here and beyond it there. An unsynchronised board also agrees with the
/// transform and not with the scene's alignment, so the edges off the board
/// must not point elsewhere; nor may the depths off the board favour the
/// optimum: a result turned by a tilted camera board has its edges' optimum
/// towards the truth, where its hole centres also lie off the camera's
/// (the tilted board moved them), and lidar depths tilted against the
/// stereo's by less than the depth rule's limit but consistently from frame
/// to frame.
///
/// Fitted to one board pose, the plane tilt refutes nothing: the fit copied
/// the camera board's normal into the transform, and that normal is what
/// hole rims fix worst on a distant board, so a wrong one turns the result
/// about the board, where the edges see it only by parallax: a white board
/// before a white wall whose rims tilt the camera board by a few degrees
/// gives a result that far off, whose edges align best a fraction of a
/// degree away, where the lidar board tilts against that camera board.
bool board_refutes(const CalibrationCheck::Report& r, const CalibrationCheck::Params& p, double fx,
                   BoardEvidence board) {
  if (!r.optimum_board) return false;
  if (std::abs(r.scene_misalignment) > p.suspect_scene_misalignment_deg * kDeg) return false;
  const CalibrationCheck::Scores& here = r.scores;
  const CalibrationCheck::Scores& there = *r.optimum_board;
  const double sigma = std::max(std::isfinite(here.depth_tilt_sigma) ? here.depth_tilt_sigma : 0.0,
                                std::isfinite(there.depth_tilt_sigma) ? there.depth_tilt_sigma : 0.0);
  if (there.depth_tilt + 2.0 * sigma < here.depth_tilt) return false;
  if (here.center_offset < p.refuting_center_offset / 3.0 && there.center_offset > p.refuting_center_offset)
    return true;
  const std::array<std::array<double, 3>, 3> measures{{
      {here.outside_fraction, there.outside_fraction, p.suspect_outside_fraction},
      {here.outline_px / fx, there.outline_px / fx, p.suspect_outline_deg * kDeg},
      {here.plane_tilt, there.plane_tilt, p.suspect_plane_tilt_deg * kDeg},
  }};
  const std::size_t tilt = 2;  // measures[tilt] is the plane tilt
  for (std::size_t k = 0; k < measures.size(); ++k) {
    if (k == tilt && board == BoardEvidence::FittedToOnePose) continue;
    const auto& [at_transform, at_optimum, suspect_at] = measures[k];
    if (std::abs(at_transform) <= 0.5 * suspect_at && std::abs(at_optimum) > suspect_at) return true;
  }
  return false;
}

void judge_edges(const CalibrationCheck::Report& r, const CalibrationCheck::Params& p, double fx, BoardEvidence board,
                 Judgement& j) {
  if (r.edge_frames == 0) {
    j.suspect.push_back("no image edges to check against: only the board was checked");
    return;
  }
  if (r.scores.edge_points < p.min_edge_points) {
    j.suspect.push_back(format("only %.0f lidar depth edges fall into the images (need %.0f): too little evidence",
                               r.scores.edge_points, static_cast<double>(p.min_edge_points)));
    return;
  }
  int best = 0;  // the degree of freedom whose scan found the best alignment
  for (int k = 1; k < 6; ++k)
    if (r.peaks[k].best_gain > r.peaks[best].best_gain) best = k;
  const auto& peak = r.peaks[best];
  j.grade(r.alignment_gain, p.suspect_alignment_gain, p.failed_alignment_gain,
          format("the lidar edges align %.0f %% better with the image elsewhere (%+.2f ", 100.0 * r.alignment_gain,
                 peak.best_offset * (peak.rotation ? 1.0 / kDeg : 100.0)) +
              (peak.rotation ? "deg in " : "cm in ") + peak.name + ")");
  const bool misalignment_counts = r.misalignment_gain >= p.min_misalignment_gain &&
                                   r.optimum_edge_score >= p.min_optimum_edge_score &&
                                   beyond_its_peak(r.peaks, p.min_misalignment_widths) &&
                                   !board_refutes(r, p, fx, board);
  if (misalignment_counts)
    j.grade(r.misalignment, p.suspect_misalignment_deg * kDeg, p.failed_misalignment_deg * kDeg,
            format("the lidar edges align best with the image %.1f px (%.2f deg) away", r.misalignment_px,
                   r.misalignment / kDeg));
  j.grade(r.scene_misalignment, p.suspect_scene_misalignment_deg * kDeg, p.failed_scene_misalignment_deg * kDeg,
          format("the lidar edges off the board align best with the image %.2f deg away, while the board's align: "
                 "the board moved between the lidar sweep and the images (sensors not synchronised?)",
                 r.scene_misalignment / kDeg));
  // A roll counts, like the misalignment, only where the edges land at its
  // optimum: a sharp roll peak among few edges on image edges (a good
  // random-scene result, 0.04 deg off, peaked 1.2 deg away at an edge score
  // of 0.17) is where the scan found a little more to lean on.
  if (r.peaks[2].prominence >= p.min_roll_prominence && r.optimum_edge_score >= p.min_optimum_edge_score)
    j.grade(r.peaks[2].offset, p.suspect_roll_deg * kDeg, p.failed_roll_deg * kDeg,
            format("the lidar edges align best with the image rolled %+.2f deg about the optical axis",
                   r.peaks[2].offset / kDeg));
  for (int k = 0; k < 2; ++k)
    if (r.peaks[k].prominence < p.min_prominence)
      j.suspect.push_back("the edge score has no clear optimum in " + r.peaks[k].name +
                          format(" (prominence %.2f)", r.peaks[k].prominence));
}

/// Of an ambiguous result: whether the checked transform alone stands both
/// sensors upright. A turn of the hole pattern about the board's normal
/// turns the lidar's up about it too, by 180 deg (or 90 on a square
/// pattern), so an upright mounting leaves one hypothesis near 0.
bool upright_only(const CalibrationCheck::Report& report, const CalibrationCheck::Params& params) {
  const double upright = params.upright_deg * kDeg;
  if (!report.ambiguous || !(upright > 0.0) || report.up_angle > upright) return false;
  for (const auto& alternative : report.alternatives)
    if (std::abs(alternative.scores.support - report.scores.support) <= params.hypothesis_margin &&
        alternative.up_angle < 2.0 * upright)
      return false;
  return true;
}

void judge_hypotheses(const CalibrationCheck::Report& r, const CalibrationCheck::Params& p, Judgement& j) {
  if (r.preferred >= 0) {
    const auto& a = r.alternatives[r.preferred];
    j.failed.push_back("the scene supports '" + a.name + "' better (support " +
                       format("%.2f vs %.2f", a.scores.support, r.scores.support) +
                       "): the hole labels of the two sensors disagree by a turn of the pattern");
  } else if (r.ambiguous) {
    std::string names;
    double nearest_up = M_PI;
    for (const auto& a : r.alternatives)
      if (std::abs(a.scores.support - r.scores.support) <= p.hypothesis_margin) {
        names += (names.empty() ? "'" : ", '") + a.name + "' (" + format("%.2f", a.scores.support) + ")";
        nearest_up = std::min(nearest_up, a.up_angle);
      }
    const std::string cannot_tell = "the scene supports " + names + " about as well as this transform (" +
                                    format("%.2f", r.scores.support) + ")";
    const std::string remedy = "add structure beside the board (a box, a post) or texture behind it";
    if (r.upright_only)
      j.suspect.push_back(cannot_tell + format("; taken because only this one stands both sensors upright (the lidar's "
                                               "+z %.0f deg from the image's up, %.0f deg or more under the others)",
                                               r.up_angle / kDeg, nearest_up / kDeg) +
                          ": if a sensor is mounted rolled or upside down, " + remedy);
    else
      j.failed.push_back("ambiguous: " + cannot_tell + "; " + remedy);
  }
}

}  // namespace

void judge(CalibrationCheck::Report& report, const CalibrationCheck::Params& params, double fx, BoardEvidence board) {
  Judgement j;
  report.upright_only = upright_only(report, params);
  if (report.board_frames == 0 && report.edge_frames == 0) {
    j.failed.push_back("no frame holds the evidence: lidar board returns with a camera board pose, or image edges");
  } else {
    judge_hypotheses(report, params, j);
    judge_board(report, params, fx, j);
    judge_edges(report, params, fx, board, j);
  }
  report.reasons = j.failed;
  report.reasons.insert(report.reasons.end(), j.suspect.begin(), j.suspect.end());
  report.verdict = !j.failed.empty() ? Verdict::Failed : !j.suspect.empty() ? Verdict::Suspect : Verdict::Ok;
}

}  // namespace l2s::detail
