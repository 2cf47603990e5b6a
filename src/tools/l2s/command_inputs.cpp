// Inputs several sub-commands share (commands.hpp).
#include "commands.hpp"

#include <l2s/frame_inspector.hpp>
#include <l2s/io/calibrator_yaml.hpp>
#include <l2s/io/ring_recovery.hpp>

#include <cstdio>

namespace l2s::cli {

io::Dataset open_dataset_warning(const std::string& folder) {
  io::Dataset dataset = io::Dataset::open(folder);
  for (const std::string& warning : dataset.warnings()) std::fprintf(stderr, "l2s: warning: %s\n", warning.c_str());
  return dataset;
}

Calibrator::Params params_from(const std::string& preset, const std::string& params_file) {
  return params_file.empty() ? Calibrator::Params::preset(preset) : io::read_calibrator_params(params_file);
}

std::string frame_path(const io::Frame& frame, const Calibrator::Params& params) {
  if (!frame.ring_recovery || params.lidar_scan != Calibrator::LidarScan::Auto)
    return lidar_path(frame.lidar, params).reason;
  const io::RingRecoveryReport& recovery = *frame.ring_recovery;
  std::string why = recovery.structure == io::ScanStructure::RingFree
                        ? "ring-free: " + recovery.structure_reason
                        : "rings from the returns (" + io::to_string(recovery.source) + "): " + recovery.structure_reason;
  if (!recovery.note.empty()) why += "; " + recovery.note;
  return why;
}

}  // namespace l2s::cli
