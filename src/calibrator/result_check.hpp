#pragma once
// The calibration check of a Calibrator's result (private).

#include <l2s/calibrator.hpp>

namespace l2s::detail {

/// Checks result.T_lidar_camera against `frames` (CalibrationCheck), with
/// the fits of the camera centroids relabelled by the target's symmetries as
/// the alternatives. When the scene clearly supports one of them, it becomes
/// the result (centroids relabelled, registration redone, labels_turned and
/// a note set) and is checked again. Fills quality and checked.
void check_result(Calibrator::Result& result, const std::vector<CheckFrame>& frames, const StereoCamera& cameras,
                  const Target& target, const Calibrator::Params& params);

}  // namespace l2s::detail
