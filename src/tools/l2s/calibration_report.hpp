#pragma once
// What `l2s calibrate` does with a lidar-camera calibration once its frames
// are in, whether they came from a dataset folder or a recording: the
// report, the overlay, the result file and the exit code.

#include "calibrate_options.hpp"

#include <l2s/calibrator.hpp>
#include <l2s/io/dataset.hpp>

#include <Eigen/Geometry>
#include <functional>
#include <optional>
#include <string>

namespace l2s::cli {

/// What a lidar-camera calibration reads besides its frames.
struct CalibrationInput {
  std::string source;          ///< the dataset folder or recording, for the result file
  std::string default_output;  ///< the result YAML when -o does not say
  std::optional<Eigen::Isometry3d> truth;  ///< ground truth, when the input has one
  /// The left image of frame `stem`, for the check's overlay (empty when
  /// there is no such frame).
  std::function<Image(const std::string& stem)> left_image;
};

/// Why a frame was not used, one line per branch (stderr).
void print_frame_failure(const FrameReport& frame);

/// Prints the counts, poses, estimate and check of `calibrator`'s result;
/// writes the overlay and (unless the check failed it and --keep-failed is
/// not given) the result. Returns the exit code: 1 when the calibration
/// failed or its check did.
int report_calibration(const CalibrateOptions& options, const CalibrationInput& input, const Calibrator& calibrator,
                       const io::Frame& last_frame);

}  // namespace l2s::cli
