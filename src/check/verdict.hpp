#pragma once
// The verdict of the calibration check from its measurements (private).

#include <l2s/calibration_check.hpp>

namespace l2s::detail {

/// How the checked transform came about, as far as the board is concerned.
enum class BoardEvidence {
  /// Made elsewhere (`l2s check`) or fitted over several board poses: the
  /// lidar board agreeing with the camera's at the transform is evidence.
  Independent,
  /// Fitted to the four hole centres of one board pose in these frames: the
  /// fit turned the lidar board onto the camera's, so their planes agree at
  /// the transform by construction.
  FittedToOnePose,
};

/// Sets report.verdict and report.reasons from the scores, peaks and
/// hypotheses already in `report`; `fx` [px] turns pixels into angles.
void judge(CalibrationCheck::Report& report, const CalibrationCheck::Params& params, double fx,
           BoardEvidence board = BoardEvidence::Independent);

}  // namespace l2s::detail
