// The last step of Calibrator::result(): the scene decides between the fits
// the four centres cannot tell apart (issue 8, "any mounting"; issue 11).

#include "calibrator/result_check.hpp"

#include "calibrator/pose_registration.hpp"
#include "check/verdict.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <string>
#include <tuple>

namespace l2s::detail {
namespace {

/// Makes the fit with the camera centroids (of every pose) relabelled by `turn` the result.
bool adopt(Calibrator::Result& result, const CalibrationCheck::Alternative& turn, double support_before,
           const Calibrator::Params& params, const SourceRange& camera_range) {
  if (!refit_relabelled(result, turn.relabel, params, camera_range)) return false;
  result.labels_turned = turn.degrees;
  char note[320];
  std::snprintf(note, sizeof note,
                "the camera's hole labels were turned by %d deg before the fit: the scene supports that fit clearly "
                "better (support %.2f vs %.2f); the labels as the sensors gave them disagree (a rig rolled against "
                "the lidar, or a lidar upside down)",
                turn.degrees, turn.scores.support, support_before);
  result.notes.push_back(note);
  return true;
}

/// The check frames with the board evidence taken out where a sensor's
/// detection was an outlier of its pose (PoseReport::*_outlier_frames): the
/// fit left that detection out, and the check must not judge the transform
/// by it either: a camera detection that took a tiled wall metres behind the
/// board for the board would put "the board" metres from the lidar's and
/// fail a right result. The frame's edges and depth stay.
std::vector<CheckFrame> without_outlier_boards(const std::vector<CheckFrame>& frames, const Calibrator::Result& result) {
  std::set<std::string> lidar_wrong, camera_wrong;
  const auto name = [&](int f) { return f >= 0 && f < static_cast<int>(result.frames.size()) ? result.frames[f].id : ""; };
  for (const PoseReport& pose : result.poses) {
    for (const int f : pose.lidar_outlier_frames) lidar_wrong.insert(name(f));
    for (const int f : pose.camera_outlier_frames) camera_wrong.insert(name(f));
  }
  std::vector<CheckFrame> out = frames;
  for (CheckFrame& frame : out) {
    if (lidar_wrong.count(frame.id)) {
      frame.lidar.board.clear();
      frame.lidar.hole_centers.clear();
    }
    if (camera_wrong.count(frame.id)) {
      frame.camera.T_camera_board.reset();
      frame.camera.board_pose_refined = false;
      frame.camera.stereo_plane.reset();
    }
  }
  return out;
}

/// Suspect when a used pose's centres rest on a bare majority of a sensor's
/// detections: the check no longer measures the board on the detections the
/// fit left out (without_outlier_boards), and when those are nearly as many
/// as the ones it kept, they may be the right ones; a fit to the wrong ones
/// puts the lidar board on the camera's by construction.
void judge_consensus(CalibrationCheck::Report& report, const Calibrator::Result& result) {
  for (std::size_t p = 0; p < result.poses.size(); ++p) {
    const PoseReport& pose = result.poses[p];
    if (!pose.used) continue;
    for (const auto& [sensor, outliers, clusters] :
         {std::tuple{"lidar", &pose.lidar_outlier_frames, &pose.lidar_centroids},
          std::tuple{"camera", &pose.camera_outlier_frames, &pose.camera_centroids}}) {
      const int left_out = static_cast<int>(outliers->size());
      const int kept = *std::min_element(clusters->counts.begin(), clusters->counts.end());
      if (left_out == 0 || kept >= 2 * left_out) continue;
      std::string frames;
      for (const int f : *outliers) frames += (frames.empty() ? "" : ", ") + std::to_string(f);
      report.reasons.push_back("the " + std::string(sensor) + "'s detections of pose " + std::to_string(p) +
                               " disagree: its centres rest on " + std::to_string(kept) + " frame(s), " +
                               std::to_string(left_out) + " left out (" + (left_out == 1 ? "frame " : "frames ") + frames +
                               "); if those were right, the result is wrong");
      if (report.verdict == CalibrationCheck::Verdict::Ok) report.verdict = CalibrationCheck::Verdict::Suspect;
    }
  }
}

/// A fit to one board pose made the lidar board agree with the camera's (BoardEvidence).
BoardEvidence board_evidence(const Calibrator::Result& result) {
  const auto used = std::count_if(result.poses.begin(), result.poses.end(), [](const PoseReport& p) { return p.used; });
  return used == 1 ? BoardEvidence::FittedToOnePose : BoardEvidence::Independent;
}

bool has_outlier_frames(const Calibrator::Result& result) {
  for (const PoseReport& pose : result.poses)
    if (!pose.lidar_outlier_frames.empty() || !pose.camera_outlier_frames.empty()) return true;
  return false;
}

}  // namespace

// The scene check compares the transform with the same sensors' data, and
// where they fix it weakly it agrees with a wrong one as well: random scene
// 1623345329 (a board at 5.5 m, fx B 145 px m) was ok with the camera turned
// 1.8 deg about the board and moved 17 cm, its edges and planes aligned.
void judge_uncertainty(CalibrationCheck::Report& report, const FitUncertainty& u, const Eigen::Isometry3d& T_lidar_camera,
                       const Calibrator::Params& params) {
  if (!u.valid) return;
  const double translation = translation_bound_95(u), rotation = rotation_bound_95(u, T_lidar_camera) * 180.0 / M_PI;
  if (translation <= params.trusted_bound_translation && rotation <= params.trusted_bound_rotation_deg) return;
  char reason[400];
  std::snprintf(reason, sizeof reason,
                "weakly observed: the data fix the transform only to +-%.0f mm and +-%.2f deg (95 %%; more than "
                "%.0f mm or %.1f deg), weakest %s; the scene cannot confirm it closer%s%s",
                translation * 1e3, rotation, params.trusted_bound_translation * 1e3, params.trusted_bound_rotation_deg,
                u.weakest_summary.c_str(), u.suggestion.empty() ? "" : "; add a pose ", u.suggestion.c_str());
  report.reasons.push_back(reason);
  if (report.verdict == CalibrationCheck::Verdict::Ok) report.verdict = CalibrationCheck::Verdict::Suspect;
}

void check_result(Calibrator::Result& result, const std::vector<CheckFrame>& kept_frames, const StereoCamera& cameras,
                  const Target& target, const Calibrator::Params& params, const SourceRange& camera_range,
                  bool labels_fixed) {
  const bool boards_go = has_outlier_frames(result);  // copy the frames only then
  const std::vector<CheckFrame> cleaned =
      boards_go ? without_outlier_boards(kept_frames, result) : std::vector<CheckFrame>{};
  const std::vector<CheckFrame>& frames = boards_go ? cleaned : kept_frames;
  const Registrar registrar(params.registrar);
  const CalibrationCheck check(cameras, target, params.check);
  const auto alternatives = [&] {
    return relabelled_alternatives(result.lidar_centroids.centers, result.camera_centroids.centers, target,
                                   registrar);
  };
  CalibrationCheck::Report report = check.check(frames, result.T_lidar_camera, alternatives());
  if (labels_fixed) {
    // The board's own labels need no vote of the scene: judged without the alternatives.
    report.alternatives.clear();
    report.preferred = -1;
    report.ambiguous = false;
  } else if (report.preferred >= 0 &&
      adopt(result, report.alternatives[report.preferred], report.scores.support, params, camera_range)) {
    const double milliseconds = report.milliseconds;
    report = check.check(frames, result.T_lidar_camera, alternatives());
    report.milliseconds += milliseconds;
  }
  // Judged again with what the check cannot know: how the fit used the board.
  judge(report, params.check, cameras.left.fx(), board_evidence(result));
  judge_consensus(report, result);
  judge_uncertainty(report, result.joint.uncertainty, result.joint.T_target_source, params);
  result.quality = std::move(report);
  result.checked = true;
}

}  // namespace l2s::detail
