#pragma once
// Calibrator files: the parameters (so users tune without recompiling) and the
// calibration result (DATASET.md transform plus what a user needs to use it).

#include <l2s/calibrator.hpp>
#include <l2s/export.hpp>

#include <string>

namespace l2s::io {

/// Reads a params file. Optional `preset: default|paper` picks the base values
/// (default: "default"); every other key overrides one field, sections as in
/// write_calibrator_params. Unknown keys are errors (a typo must not be ignored).
/// Throws FileError naming the file and key; the result is validated.
L2S_EXPORT Calibrator::Params read_calibrator_params(const std::string& path);

/// Writes every field of `params`, atomically.
L2S_EXPORT void write_calibrator_params(const std::string& path, const Calibrator::Params& params,
                             const std::string& preset_comment = "");

/// Writes a calibration result atomically: T_lidar_camera (DATASET.md), its
/// inverse, quaternion, roll/pitch/yaw, ROS static_transform_publisher
/// arguments for both directions, centroids, residuals, the `quality`
/// section of the scene check (verdict, reasons, scores, per-DoF peaks,
/// alternatives; when result.checked) and per-frame diagnostics.
/// Throws InputError("result", ...) for a result that is not found (nothing is
/// written, an existing file stays), FileError when the file cannot be written.
L2S_EXPORT void write_calibration_result(const std::string& path, const Calibrator::Result& result,
                              const std::string& dataset = "", const std::string& preset = "");

}  // namespace l2s::io
