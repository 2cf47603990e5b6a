#pragma once
// The result file of a lidar-lidar calibration: DATASET.md's T_lidar_lidar2
// first (tools that compare read only that key), then what a user needs to
// apply and judge it.

#include <l2s/export.hpp>
#include <l2s/lidar_pair_calibrator.hpp>

#include <string>

namespace l2s::io {

/// Writes the result atomically: T_lidar_lidar2 (DATASET.md), its inverse,
/// quaternion and roll/pitch/yaw, ROS static_transform_publisher arguments,
/// residuals, the poses with uncertainty and leave-one-pose-out shifts, the
/// sanity check and per-frame diagnostics. Throws InputError("result", ...)
/// for a result that is not found (nothing is written), FileError when the
/// file cannot be written.
L2S_EXPORT void write_lidar_pair_result(const std::string& path, const LidarPairCalibrator::Result& result,
                                        const std::string& dataset = "", const std::string& preset = "");

}  // namespace l2s::io
