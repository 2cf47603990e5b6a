#pragma once
// The calibration check of a Calibrator's result (private).

#include <l2s/calibrator.hpp>

namespace l2s::detail {

/// Checks result.T_lidar_camera against `frames` (CalibrationCheck), with
/// the fits of the camera centroids relabelled by the target's symmetries as
/// the alternatives. When the scene clearly supports one of them, it becomes
/// the result (centroids relabelled, registration redone, labels_turned and
/// a note set) and is checked again. Fills quality and checked.
/// `labels_fixed`: the camera's labels come from the board itself (a mono
/// camera reads them off the markers), so no relabelled alternatives are
/// weighed: without stereo depth the scene often cannot tell a 180 deg turn
/// of the symmetric hole pattern, and the markers already do.
void check_result(Calibrator::Result& result, const std::vector<CheckFrame>& frames, const StereoCamera& cameras,
                  const Target& target, const Calibrator::Params& params, bool labels_fixed = false);

}  // namespace l2s::detail
