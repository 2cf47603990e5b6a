// The last step of Calibrator::result(): the scene decides between the fits
// the four centres cannot tell apart (issue 8, "any mounting"; issue 11).

#include "calibrator/result_check.hpp"

#include "calibrator/pose_registration.hpp"
#include "check/verdict.hpp"

#include <cstdio>

namespace l2s::detail {
namespace {

/// Makes the fit with the camera centroids (of every pose) relabelled by `turn` the result.
bool adopt(Calibrator::Result& result, const CalibrationCheck::Alternative& turn, double support_before,
           const Calibrator::Params& params) {
  if (!refit_relabelled(result, turn.relabel, params)) return false;
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

void check_result(Calibrator::Result& result, const std::vector<CheckFrame>& frames, const StereoCamera& cameras,
                  const Target& target, const Calibrator::Params& params, bool labels_fixed) {
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
      adopt(result, report.alternatives[report.preferred], report.scores.support, params)) {
    const double milliseconds = report.milliseconds;
    report = check.check(frames, result.T_lidar_camera, alternatives());
    report.milliseconds += milliseconds;
  }
  result.quality = std::move(report);
  result.checked = true;
}

}  // namespace l2s::detail
