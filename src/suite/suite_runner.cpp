// One group of suite cells: the frames are simulated once, the stereo branch
// runs once per preset and frame (it does not depend on the lidar), and every
// cell's Calibrator gets its own lidar sweep with the shared camera report.

#include <l2s/sim/suite.hpp>

#include <l2s/calibrator.hpp>
#include <l2s/error.hpp>
#include <l2s/fit_uncertainty.hpp>
#include <l2s/metrics.hpp>
#include <l2s/pose.hpp>
#include <l2s/sim/random_scene.hpp>
#include <l2s/sim/simulation.hpp>

#include "suite/suite_poses.hpp"

#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <optional>

namespace l2s::sim {

namespace detail {

namespace {

/// DoFs (of six) of `T` whose true error lies within the stated 95 % bound
/// of `u`; -1 when `u` is not valid.
int covered_dofs(const Eigen::Isometry3d& T, const FitUncertainty& u, const Eigen::Isometry3d& T_true) {
  if (!u.valid) return -1;
  const Eigen::Vector3d dt = T.translation() - T_true.translation();
  const Eigen::Vector3d drpy = roll_pitch_yaw(T.rotation()) - roll_pitch_yaw(T_true.rotation());
  int covered = 0;
  for (int k = 0; k < 6; ++k)
    covered += std::abs(k < 3 ? dt[k] : std::remainder(drpy[k - 3], 2.0 * M_PI)) <= u.bound_95[k];
  return covered;
}

}  // namespace

void set_outcome(SuiteRow& row, bool found, const std::string& reason, const Eigen::Isometry3d& T,
                 const FitUncertainty& u, const Eigen::Isometry3d& T_true) {
  row.success = found;
  row.reason = reason;
  if (!found) return;
  row.covered = covered_dofs(T, u, T_true);
  if (u.valid) {
    row.bound_t = translation_bound_95(u);
    row.bound_r = rotation_bound_95(u, T);
  }
  const PoseError error = pose_error(T, T_true);
  row.e_t = error.translation;
  row.e_r = error.rotation;
}

void set_verdict(SuiteRow& row, CalibrationCheck::Verdict verdict, const std::vector<std::string>& reasons) {
  row.verdict = verdict_name(verdict);
  for (const std::string& reason : reasons)
    row.check_reasons += (row.check_reasons.empty() ? "" : " | ") + reason;  // reasons hold "; " themselves
}

SuiteRow evaluate(const SuiteCell& cell, const Calibrator::Result& result, const Eigen::Isometry3d& T_true,
                  double wall_s, const std::string& scene) {
  SuiteRow row = SuiteRow::of(cell);
  row.scene = scene;
  if (result.checked) set_verdict(row, result.quality.verdict, result.quality.reasons);
  set_outcome(row, result.found, result.reason, result.T_lidar_camera, result.joint.uncertainty, T_true);
  row.frames = result.frames_added;
  row.lidar_frames = result.lidar_frames;
  row.camera_frames = result.camera_frames;
  row.wall_s = wall_s;
  return row;
}

}  // namespace detail

namespace {

using detail::evaluate;

double rms_distance(const HoleCenters& found, const HoleCenters& truth) {
  double sum = 0.0;
  for (std::size_t h = 0; h < found.size(); ++h) sum += (found[h] - truth[h]).squaredNorm();
  return std::sqrt(sum / static_cast<double>(found.size()));
}

// Which branch an error comes from: each sensor's centres against the truth.
SuiteRow with_centre_errors(SuiteRow row, const Calibrator::Result& result, const DatasetSimulator& simulator) {
  if (!result.found) return row;
  const DatasetSimulator::HoleTruth truth = simulator.true_hole_centers();
  row.e_lidar_centres = rms_distance(result.lidar_centroids.centers, truth.lidar);
  row.e_camera_centres = rms_distance(result.camera_centroids.centers, truth.camera);
  return row;
}

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}


// A cell in progress: its calibrator and the time spent on it so far.
struct Run {
  const SuiteCell* cell = nullptr;
  std::string unable;  // why the cell has no calibrator (a mono camera and a board without markers)
  const DatasetSimulator* simulator = nullptr;
  std::optional<Calibrator> calibrator;
  std::optional<AccumulatedLidar> accumulated;  // a `lidar: accumulated` scene's cloud, detected once
  double seconds = 0.0;
};

// The group's simulated data: one simulator per lidar, or why it could not be built.
struct GroupData {
  std::map<std::string, std::unique_ptr<DatasetSimulator>> simulators;
  std::map<std::string, std::string> failures;  // lidar -> reason
  const DatasetSimulator* source = nullptr;     // renders the shared frames (images)
  std::string scene;                            // what a random scene drew
};

/// What a random scene drew, in the row's own columns.
SuiteRow with_scene_draw(SuiteRow row, const SimulationConfig& config) {
  row.face = name_of(config.appearance.board);
  if (config.target.markers) row.markers = config.target.markers->dictionary;
  row.roll = std::remainder(config.rig.roll, 2.0 * M_PI);
  row.lens = config.rig.images() == ImageKind::Raw ? std::string("raw ") + name_of(config.rig.lenses[0].distortion.model)
                                                   : "rectified";
  return row;
}

// One simulator per lidar; the first that places the board fixes the pose
// for the others, so they render the same scene (and the same images).
GroupData simulate_group(const SuiteGroup& group, const std::vector<SuiteCell>& cells, int threads) {
  GroupData data;
  for (const auto& cell : cells) {
    if (data.simulators.count(cell.lidar) || data.failures.count(cell.lidar)) continue;
    if (group.experiment == "scenes") {
      try {
        RandomScene drawn = make_random_scene(group.seed, group.frames, group.noise_k, threads, group.boards);
        data.scene = drawn.summary;
        data.source = drawn.simulator.get();
        data.simulators[cell.lidar] = std::move(drawn.simulator);
      } catch (const Error& error) {
        data.failures[cell.lidar] = std::string("simulation: ") + error.what();
      }
      continue;
    }
    SimulationConfig config = SimulationConfig::paper(group.setting, cell.lidar);
    config.frames = group.frames;
    config.noise_factor = group.noise_k;
    config.seed = group.seed;
    config.threads = threads;
    if (data.source) config.board_pose = data.source->board_pose();
    try {
      auto simulator = std::make_unique<DatasetSimulator>(config);
      if (!data.source) data.source = simulator.get();
      data.simulators[cell.lidar] = std::move(simulator);
    } catch (const Error& error) {
      data.failures[cell.lidar] = std::string("simulation: ") + error.what();
    }
  }
  return data;
}

bool is_mono(const SuiteCell& cell) { return cell.preset == "mono"; }

/// The lidar side is one cloud accumulated over the static board (DATASET.md
/// `lidar: accumulated`), not a sweep per frame.
bool accumulated(const DatasetSimulator& simulator) { return simulator.config().accumulated_seconds > 0.0; }

// A calibrator for every cell that has data: the stereo pair with the cell's
// preset, or for "mono" the left camera alone with the default preset.
std::vector<Run> start_runs(const std::vector<SuiteCell>& cells, const GroupData& data) {
  std::vector<Run> runs;
  for (const auto& cell : cells) {
    if (data.failures.count(cell.lidar)) continue;
    const DatasetSimulator& simulator = *data.simulators.at(cell.lidar);
    const StereoCamera cameras = simulator.cameras();
    const Target& target = simulator.config().target;
    Run run;
    run.cell = &cell;
    run.simulator = &simulator;
    if (!is_mono(cell))
      run.calibrator.emplace(cameras, target, Calibrator::Params::preset(cell.preset));
    else if (target.markers)
      run.calibrator.emplace(cameras.left, cameras.images, target, Calibrator::Params::preset("default"));
    else
      run.unable = "the board carries no markers: one camera alone cannot find it";
    runs.push_back(std::move(run));
  }
  return runs;
}

using Evaluations = std::map<const SuiteCell*, std::vector<SuiteRow>>;

// Frame i into every run, evaluating the runs whose cell asks for it.
void add_frame(int i, const SuiteGroup& group, const GroupData& data, std::vector<Run>& runs,
               Evaluations& evaluations) {
  SimulatedFrame frame = data.source->frame(i);
  std::map<std::string, LidarCloud> sweeps;
  for (const auto& [lidar, simulator] : data.simulators)
    if (!accumulated(*simulator))
      sweeps[lidar] = simulator.get() == data.source ? std::move(frame.lidar) : simulator->sweep(i);
  // The camera branch once per preset: its parameters are the same for every lidar.
  std::map<std::string, BranchReport> camera;
  for (const Run& run : runs)
    if (run.calibrator && !camera.count(run.cell->preset))
      camera[run.cell->preset] = is_mono(*run.cell) ? run.calibrator->camera_branch(frame.left)
                                                    : run.calibrator->camera_branch(frame.left, frame.right);

  const std::string id = std::to_string(i);
  for (Run& run : runs) {
    if (!run.calibrator) {
      if (!run.cell->every_frame && i + 1 < group.frames) continue;
      SuiteRow row = SuiteRow::of(*run.cell);
      row.scene = data.scene;
      row.frames = i + 1;
      row.reason = run.unable;
      if (group.experiment == "scenes") row = with_scene_draw(std::move(row), run.simulator->config());
      evaluations[run.cell].push_back(std::move(row));
      continue;
    }
    // An accumulated cloud is made once (not timed: it is the data) and
    // detected once, with the first frame, whose time that counts in.
    std::optional<LidarCloud> cloud;
    if (accumulated(*run.simulator) && !run.accumulated) cloud = run.simulator->accumulated_cloud();
    const auto start = Clock::now();
    if (cloud) run.accumulated = run.calibrator->detect_accumulated(*cloud);
    if (run.accumulated)
      run.calibrator->add(*run.accumulated, camera.at(run.cell->preset), id);
    else
      run.calibrator->add(sweeps.at(run.cell->lidar), camera.at(run.cell->preset), id);
    const bool evaluated = run.cell->every_frame || i + 1 == group.frames;
    std::optional<Calibrator::Result> result;
    if (evaluated) result = run.calibrator->result();
    run.seconds += seconds_since(start) + camera.at(run.cell->preset).milliseconds * 1e-3;
    if (!result) continue;
    SuiteRow row = with_centre_errors(
        evaluate(*run.cell, *result, run.simulator->T_lidar_camera(), run.seconds, data.scene), *result,
        *run.simulator);
    if (group.experiment == "scenes") row = with_scene_draw(std::move(row), run.simulator->config());
    evaluations[run.cell].push_back(std::move(row));
  }
}

// The rows in the cells' order. A cell without data fails at every frame
// count it would have had (no data, so no evaluation).
std::vector<SuiteRow> rows_of(const std::vector<SuiteCell>& cells, const GroupData& data,
                              Evaluations& evaluations) {
  std::vector<SuiteRow> rows;
  for (const auto& cell : cells) {
    if (const auto failed = data.failures.find(cell.lidar); failed != data.failures.end()) {
      for (int n = cell.every_frame ? 1 : cell.frames; n <= cell.frames; ++n) {
        SuiteRow row = SuiteRow::of(cell);
        row.frames = n;
        row.reason = failed->second;
        rows.push_back(row);
      }
      continue;
    }
    for (auto& row : evaluations[&cell]) rows.push_back(std::move(row));
  }
  return rows;
}

}  // namespace

std::vector<SuiteRow> run_suite_group(const SuiteGroup& group, const std::vector<SuiteCell>& cells,
                                      int threads, const std::function<void()>& on_frame) {
  if (is_pose_experiment(group.experiment)) return detail::run_poses_group(group, cells, threads, on_frame);
  const GroupData data = simulate_group(group, cells, threads);
  std::vector<Run> runs = start_runs(cells, data);
  Evaluations evaluations;
  for (int i = 0; i < group.frames && data.source; ++i) {
    add_frame(i, group, data, runs, evaluations);
    if (on_frame) on_frame();
  }
  if (!data.source && on_frame)
    for (int i = 0; i < group.frames; ++i) on_frame();
  return rows_of(cells, data, evaluations);
}

}  // namespace l2s::sim
