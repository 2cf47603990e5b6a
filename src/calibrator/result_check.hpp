#pragma once
// The calibration check of a Calibrator's result (private).

#include "calibrator/pose_registration.hpp"

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
/// An ok verdict becomes suspect when the result's own 95 % bounds exceed
/// params.trusted_bound_* (`camera_range`: for a relabelled refit).
void check_result(Calibrator::Result& result, const std::vector<CheckFrame>& frames, const StereoCamera& cameras,
                  const Target& target, const Calibrator::Params& params, const SourceRange& camera_range,
                  bool labels_fixed = false);

/// Makes an ok `report` suspect, with the reason, when the 95 % bounds of `u`
/// (the fit's of T_lidar_camera) exceed params.trusted_bound_*
/// (translation_bound_95, rotation_bound_95).
void judge_uncertainty(CalibrationCheck::Report& report, const FitUncertainty& u, const Eigen::Isometry3d& T_lidar_camera,
                       const Calibrator::Params& params);

}  // namespace l2s::detail
