#pragma once
// The verdict of the calibration check from its measurements (private).

#include <l2s/calibration_check.hpp>

namespace l2s::detail {

/// Sets report.verdict and report.reasons from the scores, peaks and
/// hypotheses already in `report`; `fx` [px] turns pixels into angles.
void judge(CalibrationCheck::Report& report, const CalibrationCheck::Params& params, double fx);

}  // namespace l2s::detail
