#pragma once
// The options of `l2s calibrate`, shared by its inputs (a dataset folder, a
// recording) and its kinds of pair (lidar-camera, lidar-lidar).

#include "commands.hpp"

#include <l2s/calibrator.hpp>
#include <l2s/recording/frame_pairing.hpp>

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

/// The options a lidar-lidar calibration takes.
inline LidarPairRun lidar_pair_run(const CalibrateOptions& options, const Calibrator::Params& params) {
  return {params, options.params_file.empty() ? options.preset : options.params_file, options.output,
          options.frames, options.verbose};
}

}  // namespace l2s::cli
