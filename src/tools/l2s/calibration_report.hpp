#pragma once
// What `l2s calibrate` does with a lidar-camera calibration once its frames
// are in, whether they came from a dataset folder or a recording: the
// report, the overlay, the result file and the exit code.

#include <l2s/calibrator.hpp>
#include <l2s/io/dataset.hpp>
#include <l2s/recording/frame_pairing.hpp>

#include <Eigen/Geometry>
#include <functional>
#include <optional>
#include <string>

namespace l2s::cli {

/// The options of `l2s calibrate`.
struct CalibrateOptions {
  std::string input;  ///< dataset folder or ROS 1 recording
  std::string output;
  std::string overlay;
  std::string params_file;
  std::string preset = "default";
  // A recording's: its board (a dataset folder has its target.yaml), topics and pairing.
  std::string target;
  RecordingTopics topics;
  PairingParams pairing;
  int frames = 0;
  int frames_ahead = 2;
  bool verbose = false;
  bool keep_failed = false;
};

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
