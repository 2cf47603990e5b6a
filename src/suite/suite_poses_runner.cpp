// The runs of the pose experiments (issue 9): one recording of five poses
// (10 frames each, 2 moving frames between), every preset's calibrator fed
// all of it, evaluated at the end of the 1st, 2nd, 3rd and 5th pose: the
// same frames for every P, so P = 3 and P = 1 compare on the same data.
//  - poses: the stereo rig and the VLP-16;
//  - mono: the rig's left camera alone, the board carrying the default
//    ArUco markers (a Calibrator of one camera);
//  - lidar-pair: the VLP-16 and an HDL-32E near it, no images
//    (LidarPairCalibrator; the error is that of T_lidar_lidar2).
// Each row's `scene` field records what the summary needs beyond the errors:
// poses asked, drawn and used, moving frames that entered a pose, and how many
// of the six DoF's errors the stated 95 % bounds covered.

#include "suite/suite_poses.hpp"

#include <l2s/calibrator.hpp>
#include <l2s/error.hpp>
#include <l2s/lidar_pair_calibrator.hpp>
#include <l2s/sim/lidar_pair.hpp>
#include <l2s/sim/multi_pose.hpp>

#include <algorithm>
#include <chrono>
#include <memory>
#include <optional>
#include <sstream>

namespace l2s::sim::detail {
namespace {

using Clock = std::chrono::steady_clock;

constexpr const char* kSecondLidar = "hdl32";  ///< lidar-pair: the issue's VLP-16 to HDL-32E

/// The recording of a group: images of a multi-pose scene (poses, mono) or
/// the sweeps of two lidars (lidar-pair).
struct PoseRecording {
  std::unique_ptr<MultiPoseSimulator> images;
  std::unique_ptr<LidarPairSimulator> lidars;

  int frames() const { return images ? images->frames() : lidars->frames(); }
  SimulatedFrame frame(int index) const { return images ? images->frame(index) : lidars->frame(index); }
  const std::vector<PoseSegment>& segments() const { return images ? images->segments() : lidars->segments(); }
  std::vector<int> moving_frames() const { return images ? images->moving_frames() : lidars->moving_frames(); }
  std::size_t poses() const { return images ? images->poses().size() : lidars->poses().size(); }
};

PoseRecording record(const SuiteGroup& group, const std::string& lidar, int threads) {
  SimulationConfig base = SimulationConfig::paper(group.setting, lidar);
  base.frames = kPoseFrames;
  base.noise_factor = group.noise_k;
  base.seed = group.seed;
  base.threads = threads;
  PoseRecording recording;
  if (group.experiment == "lidar-pair") {
    LidarPairConfig config;
    config.base = base;
    config.lidar2 = kSecondLidar;
    config.poses = kMostPoses;
    config.moving_frames = kMovingFrames;
    recording.lidars = std::make_unique<LidarPairSimulator>(config);
    return recording;
  }
  if (group.experiment == "mono") {
    base.mono = true;
    if (!base.target.markers) base.target.markers = MarkerLayout::corners_default();
  }
  MultiPoseConfig config;
  config.base = base;
  config.poses = kMostPoses;
  config.moving_frames = kMovingFrames;
  recording.images = std::make_unique<MultiPoseSimulator>(config);
  return recording;
}

/// The `scene` record of a row: what the poses summary reads back.
template <class Result>
std::string pose_record(const Result& result, const PoseRecording& recording, int asked, int covered) {
  const std::vector<int> moving = recording.moving_frames();
  int entered = 0;
  for (const auto& pose : result.poses)
    for (int f : pose.frames) entered += std::count(moving.begin(), moving.end(), f) > 0;
  std::ostringstream scene;
  scene << "poses=" << asked << " drawn=" << std::min<std::size_t>(asked, recording.poses())
        << " found=" << result.poses.size() << " used=" << result.poses_used() << " moving_in_poses=" << entered;
  if (result.found) scene << " covered=" << std::max(0, covered) << " valid=" << result.joint.uncertainty.valid;
  return scene.str();
}

/// One cell's calibration over the recording.
class PoseCellRun {
 public:
  virtual ~PoseCellRun() = default;
  virtual void add(const SimulatedFrame& frame, int index) = 0;
  /// The cell's row after the first `asked` poses (its wall time left to the caller).
  virtual SuiteRow evaluate(const PoseRecording& recording, int asked) const = 0;
};

/// A camera (stereo pair or the left camera alone) against the lidar.
class CameraRun : public PoseCellRun {
 public:
  CameraRun(const SuiteCell& cell, const MultiPoseSimulator& sim)
      : cell_(cell),
        mono_(sim.config().base.mono),
        calibrator_(mono_ ? Calibrator(sim.cameras().left, sim.cameras().images, sim.config().base.target,
                                       Calibrator::Params::preset(cell.preset))
                          : Calibrator(sim.cameras(), sim.config().base.target, Calibrator::Params::preset(cell.preset))),
        T_true_(sim.T_lidar_camera()) {}

  void add(const SimulatedFrame& frame, int index) override {
    if (mono_)
      calibrator_.add(frame.lidar, frame.left, std::to_string(index));
    else
      calibrator_.add(frame.lidar, frame.left, frame.right, std::to_string(index));
  }

  SuiteRow evaluate(const PoseRecording& recording, int asked) const override {
    const Calibrator::Result result = calibrator_.result();
    SuiteRow row = detail::evaluate(cell_, result, T_true_, 0.0, "");
    row.scene = pose_record(result, recording, asked, row.covered);
    return row;
  }

 private:
  SuiteCell cell_;
  bool mono_;
  Calibrator calibrator_;
  Eigen::Isometry3d T_true_;
};

/// The second lidar against the first.
class LidarPairRun : public PoseCellRun {
 public:
  LidarPairRun(const SuiteCell& cell, const LidarPairSimulator& sim)
      : cell_(cell),
        calibrator_(sim.config().base.target, Calibrator::Params::preset(cell.preset)),
        T_true_(sim.T_lidar_lidar2()) {}

  void add(const SimulatedFrame& frame, int index) override {
    calibrator_.add(frame.lidar, frame.lidar2, std::to_string(index));
  }

  SuiteRow evaluate(const PoseRecording& recording, int asked) const override {
    const LidarPairCalibrator::Result result = calibrator_.result();
    SuiteRow row = SuiteRow::of(cell_);
    set_verdict(row, result.check.verdict, result.check.reasons);
    set_outcome(row, result.found, result.reason, result.T_lidar_lidar2, result.joint.uncertainty, T_true_);
    row.frames = result.frames_added;
    row.lidar_frames = result.lidar_frames;
    row.camera_frames = result.lidar2_frames;  // the second sensor's column
    row.scene = pose_record(result, recording, asked, row.covered);
    return row;
  }

 private:
  SuiteCell cell_;
  LidarPairCalibrator calibrator_;
  Eigen::Isometry3d T_true_;
};

std::unique_ptr<PoseCellRun> start_run(const SuiteCell& cell, const PoseRecording& recording) {
  if (recording.lidars) return std::make_unique<LidarPairRun>(cell, *recording.lidars);
  return std::make_unique<CameraRun>(cell, *recording.images);
}

/// Frame index after which the first `poses` static poses are complete.
int last_frame_of(const PoseRecording& recording, int poses) {
  int last = -1, seen = 0;
  for (const PoseSegment& s : recording.segments())
    if (s.pose_index >= 0 && seen++ < poses) last = s.first_frame + s.frames - 1;
  return last;
}

}  // namespace

std::vector<SuiteRow> run_poses_group(const SuiteGroup& group, const std::vector<SuiteCell>& cells, int threads,
                                      const std::function<void()>& on_frame) {
  std::optional<PoseRecording> recording;
  std::string failure;
  try {
    recording = record(group, cells.empty() ? "vlp16" : cells.front().lidar, threads);
  } catch (const Error& error) {
    failure = std::string("simulation: ") + error.what();
  }
  std::vector<SuiteRow> rows;
  if (!recording) {
    for (const SuiteCell& cell : cells)
      for (int p : {1, 2, 3, 5}) {
        SuiteRow row = SuiteRow::of(cell);
        row.frames = pose_recording_frames(p);
        row.reason = failure;
        rows.push_back(row);
      }
    for (int i = 0; i < group.frames && on_frame; ++i) on_frame();
    return rows;
  }
  std::vector<std::unique_ptr<PoseCellRun>> runs;
  std::vector<double> seconds(cells.size(), 0.0);
  for (const SuiteCell& cell : cells) runs.push_back(start_run(cell, *recording));
  std::vector<std::vector<SuiteRow>> per_cell(cells.size());
  const auto since = [](Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); };
  for (int i = 0; i < recording->frames(); ++i) {
    const SimulatedFrame frame = recording->frame(i);
    for (std::size_t c = 0; c < cells.size(); ++c) {
      const auto start = Clock::now();
      runs[c]->add(frame, i);
      seconds[c] += since(start);
      for (int p : {1, 2, 3, 5}) {
        // Fewer poses drawn than asked: the largest P is evaluated at the end.
        if (std::min(last_frame_of(*recording, p), recording->frames() - 1) != i) continue;
        const auto evaluated = Clock::now();
        SuiteRow row = runs[c]->evaluate(*recording, p);
        seconds[c] += since(evaluated);
        row.wall_s = seconds[c];
        per_cell[c].push_back(std::move(row));
      }
    }
    if (on_frame) on_frame();
  }
  for (int i = recording->frames(); i < group.frames && on_frame; ++i) on_frame();
  for (auto& cell_rows : per_cell) rows.insert(rows.end(), cell_rows.begin(), cell_rows.end());
  return rows;
}

}  // namespace l2s::sim::detail
