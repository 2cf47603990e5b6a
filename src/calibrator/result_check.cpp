// The last step of Calibrator::result(): the scene decides between the fits
// the four centres cannot tell apart (issue 8, "any mounting"; issue 11).

#include "calibrator/result_check.hpp"

#include "calibrator/pose_registration.hpp"
#include "check/verdict.hpp"

#include <cmath>
#include <cstdio>

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

void check_result(Calibrator::Result& result, const std::vector<CheckFrame>& frames, const StereoCamera& cameras,
                  const Target& target, const Calibrator::Params& params, const SourceRange& camera_range,
                  bool labels_fixed) {
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
    report.reasons.clear();
    judge(report, params.check, cameras.left.fx());
  } else if (report.preferred >= 0 &&
      adopt(result, report.alternatives[report.preferred], report.scores.support, params, camera_range)) {
    const double milliseconds = report.milliseconds;
    report = check.check(frames, result.T_lidar_camera, alternatives());
    report.milliseconds += milliseconds;
  }
  judge_uncertainty(report, result.joint.uncertainty, result.joint.T_target_source, params);
  result.quality = std::move(report);
  result.checked = true;
}

}  // namespace l2s::detail
