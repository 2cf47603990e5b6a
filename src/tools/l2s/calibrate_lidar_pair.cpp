// l2s calibrate on a lidar-lidar dataset (lidar/ + lidar2/): streams both
// sweeps of each frame through the LidarPairCalibrator, prints the transform,
// its poses and uncertainty and the sanity check, and writes the result.

#include "commands.hpp"
#include "progress_bar.hpp"

#include <l2s/io/lidar_pair_yaml.hpp>
#include <l2s/lidar_pair_calibrator.hpp>
#include <l2s/metrics.hpp>
#include <l2s/pose.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

namespace fs = std::filesystem;

namespace l2s::cli {
namespace {

void print_branch_failure(const std::string& id, const char* side, const BranchReport& branch) {
  if (!branch.found && branch.failed_stage != "accumulating")
    std::fprintf(stderr, "  frame %s %s: %s: %s\n", id.c_str(), side, branch.failed_stage.c_str(),
                 branch.reason.c_str());
}

void add_frames(const io::Dataset& dataset, LidarPairCalibrator& calibrator, std::size_t count, bool verbose) {
  ProgressBar progress("calibrate", count);
  for (std::size_t i = 0; i < count; ++i) {
    const io::Frame frame = dataset.load(i);
    const LidarPairFrameReport report = calibrator.add(frame.lidar, frame.lidar2, frame.stem);
    if (verbose) {
      print_branch_failure(report.id, "lidar", report.lidar);
      print_branch_failure(report.id, "lidar2", report.lidar2);
    }
    progress.update(i + 1);
  }
  progress.finish();
}

void print_pose(const char* label, const Eigen::Isometry3d& T) {
  const Eigen::Vector3d t = T.translation();
  const Eigen::Vector3d rpy = roll_pitch_yaw(T.rotation());
  std::printf("%-10s t = (%8.4f, %8.4f, %8.4f) m   rpy = (%8.4f, %8.4f, %8.4f) rad\n", label, t.x(), t.y(), t.z(),
              rpy[0], rpy[1], rpy[2]);
}

void print_poses(const LidarPairCalibrator::Result& result) {
  std::printf("poses     %zu found, %d used; %zu frames skipped while the board moved\n", result.poses.size(),
              result.poses_used(), result.moving_frames.size());
  for (std::size_t p = 0; p < result.poses.size(); ++p) {
    const LidarPairPoseReport& pose = result.poses[p];
    std::printf("  pose %zu  frames %d-%d (%zu)", p, pose.first_frame, pose.last_frame, pose.frames.size());
    if (std::isfinite(pose.rms)) std::printf("  rms %.2f mm", pose.rms * 1e3);
    if (!pose.used) std::printf("  not used: %s", pose.reason.c_str());
    std::printf("\n");
  }
}

void print_uncertainty(const LidarPairCalibrator::Result& result) {
  const FitUncertainty& u = result.joint.uncertainty;
  if (!u.valid) return;
  std::printf("uncertainty (1 sigma / 95 %%, from %d residual dof):\n ", u.dof);
  for (int k = 0; k < 6; ++k) {
    const double unit = k < 3 ? 1e3 : 180.0 / M_PI;
    std::printf(" %s %.2f/%.2f %s", dof_names()[k], u.sigma[k] * unit, u.bound_95[k] * unit, k < 3 ? "mm" : "deg");
  }
  std::printf("\n");
  for (std::size_t k = 0, used = 0; k < result.poses.size(); ++k) {
    if (!result.poses[k].used || used >= result.joint.leave_one_out.size()) continue;
    const auto& loo = result.joint.leave_one_out[used++];
    std::printf("  without pose %zu: moves %.2f mm, %.3f deg\n", k, loo.translation * 1e3, loo.rotation * 180.0 / M_PI);
  }
  if (!u.suggestion.empty())
    std::printf("advice    the fit is poorly conditioned (condition %.1f, weakest: %s): add a pose %s\n", u.condition,
                u.weakest_summary.c_str(), u.suggestion.c_str());
}

void print_estimate(const io::Dataset& dataset, const LidarPairCalibrator::Result& result) {
  print_pose("estimate", result.T_lidar_lidar2);
  std::printf("residual  rms %.2f mm over the hole centres of %d pose(s)\n", result.registration.rms * 1e3,
              std::max(1, result.poses_used()));
  print_uncertainty(result);
  for (const auto& note : result.notes) std::printf("note      %s\n", note.c_str());
  std::printf("check     %s: largest pose rms %.2f mm\n", verdict_name(result.check.verdict),
              result.check.max_pose_rms * 1e3);
  for (const auto& reason : result.check.reasons) std::fprintf(stderr, "  check: %s\n", reason.c_str());
  if (const auto truth = dataset.ground_truth()) {
    print_pose("truth", *truth);
    const PoseError error = pose_error(result.T_lidar_lidar2, *truth);
    std::printf("error     e_t = %.1f mm, e_r = %.3f deg\n", error.translation * 1e3, error.rotation * 180.0 / M_PI);
  }
}

}  // namespace

int calibrate_lidar_pair(const io::Dataset& dataset, const LidarPairRun& run) {
  LidarPairCalibrator calibrator(dataset.target(), run.params);
  const std::size_t count = run.frames > 0 ? std::min<std::size_t>(run.frames, dataset.size()) : dataset.size();
  add_frames(dataset, calibrator, count, run.verbose);
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
  const std::string output =
      run.output.empty() ? (fs::path(dataset.folder()) / "calibration.yaml").string() : run.output;
  io::write_lidar_pair_result(output, result, dataset.folder(), run.preset);
  print_estimate(dataset, result);
  std::printf("wrote     %s\n", output.c_str());
  return 0;
}

}  // namespace l2s::cli
