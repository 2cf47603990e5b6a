// l2s calibrate on a lidar-lidar dataset (lidar/ + lidar2/) or recording:
// streams both sweeps of each frame through the LidarPairCalibrator, prints the transform,
// its poses and uncertainty and the sanity check, and writes the result.

#include "commands.hpp"
#include "pose_printing.hpp"
#include "progress_bar.hpp"

#include <l2s/io/lidar_pair_yaml.hpp>
#include <l2s/lidar_pair_calibrator.hpp>
#include <l2s/metrics.hpp>
#include <l2s/pose.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace l2s::cli {
namespace {

void print_branch_failure(const std::string& id, const char* side, const BranchReport& branch) {
  if (!branch.found && branch.failed_stage != "accumulating")
    std::fprintf(stderr, "  frame %s %s: %s: %s\n", id.c_str(), side, branch.failed_stage.c_str(),
                 branch.reason.c_str());
}

void add_frames(const LidarPairInput& input, LidarPairCalibrator& calibrator, std::size_t count, bool verbose) {
  ProgressBar progress("calibrate", count);
  std::size_t added = 0;
  input.read_frames(count, [&](const io::Frame& frame) {
    const LidarPairFrameReport report = calibrator.add(frame.lidar, frame.lidar2, frame.stem);
    if (verbose) {
      print_branch_failure(report.id, "lidar", report.lidar);
      print_branch_failure(report.id, "lidar2", report.lidar2);
    }
    progress.update(++added);
  });
  progress.finish();
}

void print_estimate(const LidarPairInput& input, const LidarPairCalibrator::Result& result) {
  print_pose("estimate", result.T_lidar_lidar2);
  std::printf("residual  rms %.2f mm over the hole centres of %d pose(s)\n", result.registration.rms * 1e3,
              std::max(1, result.poses_used()));
  print_uncertainty(result.joint, used_poses(result.poses));
  for (const auto& note : result.notes) std::printf("note      %s\n", note.c_str());
  std::printf("check     %s: largest pose rms %.2f mm\n", verdict_name(result.check.verdict),
              result.check.max_pose_rms * 1e3);
  for (const auto& reason : result.check.reasons) std::fprintf(stderr, "  check: %s\n", reason.c_str());
  if (input.truth) {
    print_pose("truth", *input.truth);
    const PoseError error = pose_error(result.T_lidar_lidar2, *input.truth);
    std::printf("error     e_t = %.1f mm, e_r = %.3f deg\n", error.translation * 1e3, error.rotation * 180.0 / M_PI);
  }
}

}  // namespace

int calibrate_lidar_pair(const LidarPairInput& input, const LidarPairRun& run) {
  LidarPairCalibrator calibrator(input.target, run.params);
  const std::size_t count = run.frames > 0 ? std::min<std::size_t>(run.frames, input.frames) : input.frames;
  add_frames(input, calibrator, count, run.verbose);
  const LidarPairCalibrator::Result result = calibrator.result();
  std::printf("lidar-lidar dataset: T_lidar_lidar2\n");
  std::printf("frames    %d: lidar found the board %d times, lidar2 %d times\n", result.frames_added,
              result.lidar_frames, result.lidar2_frames);
  std::printf("time      %.1f ms/frame lidar, %.1f ms/frame lidar2\n",
              result.lidar_ms / std::max(1, result.frames_added), result.lidar2_ms / std::max(1, result.frames_added));
  print_poses(result);
  if (!result.found) {
    std::fprintf(stderr, "l2s: calibration failed: %s\n", result.reason.c_str());
    return 1;
  }
  const std::string output = run.output.empty() ? input.default_output : run.output;
  io::write_lidar_pair_result(output, result, input.source, run.preset);
  print_estimate(input, result);
  std::printf("wrote     %s\n", output.c_str());
  return 0;
}

}  // namespace l2s::cli
