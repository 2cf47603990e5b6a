#pragma once
// The suite's pose experiments (issue 9: "poses" with the stereo rig,
// "mono" with its left camera alone, "lidar-pair" with a second lidar): one
// recording of five board poses per setting, calibrated once per preset and
// evaluated after the first 1, 2, 3 and 5 poses; with the uncertainty's
// coverage of the true error and any moving frame that entered a pose
// (private).

#include <l2s/calibrator.hpp>
#include <l2s/sim/suite.hpp>

#include <sstream>
#include <string>
#include <vector>

namespace l2s::sim::detail {

constexpr int kPoseFrames = 10;   ///< frames per pose
constexpr int kMovingFrames = 2;  ///< frames between two poses
constexpr int kMostPoses = 5;
/// Frames of the recording with the first `poses` poses.
constexpr int pose_recording_frames(int poses) { return poses * kPoseFrames + (poses - 1) * kMovingFrames; }

/// A row's outcome from a calibration's transform `T`: success and reason,
/// and when found its errors against T_true and how many DoFs (of six) the
/// stated 95 % bounds of `u` cover (-1 when `u` is not valid).
void set_outcome(SuiteRow& row, bool found, const std::string& reason, const Eigen::Isometry3d& T,
                 const FitUncertainty& u, const Eigen::Isometry3d& T_true);

/// A row's check verdict and its reasons, joined by " | ".
void set_verdict(SuiteRow& row, CalibrationCheck::Verdict verdict, const std::vector<std::string>& reasons);

/// A cell's row from its calibration: success, reason, frames, verdict, the
/// errors against T_true when a transform was found, and their coverage.
SuiteRow evaluate(const SuiteCell& cell, const Calibrator::Result& result, const Eigen::Isometry3d& T_true,
                  double wall_s, const std::string& scene);

/// Runs a group of the poses experiment (as run_suite_group).
std::vector<SuiteRow> run_poses_group(const SuiteGroup& group, const std::vector<SuiteCell>& cells, int threads,
                                      const std::function<void()>& on_frame);

/// The section of a pose experiment in summary.md.
void write_poses_summary(std::ostringstream& out, const std::string& experiment,
                         const std::vector<const SuiteRow*>& rows);

}  // namespace l2s::sim::detail
