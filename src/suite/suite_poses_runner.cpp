// The poses experiment's runs: a MultiPoseSimulator recording of five poses
// (10 frames each, 2 moving frames between), every preset's Calibrator fed
// all of it, evaluated at the end of the 1st, 2nd, 3rd and 5th pose: the
// same frames for every P, so P = 3 and P = 1 compare on the same data.
// Each row's `scene` field records what the summary needs beyond the errors:
// poses asked, drawn and used, moving frames that entered a pose, and how many
// of the six DoF's errors the stated 95 % bounds covered.

#include "suite/suite_poses.hpp"

#include <l2s/calibrator.hpp>
#include <l2s/error.hpp>
#include <l2s/fit_uncertainty.hpp>
#include <l2s/metrics.hpp>
#include <l2s/pose.hpp>
#include <l2s/sim/multi_pose.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <optional>
#include <sstream>

namespace l2s::sim::detail {
namespace {

using Clock = std::chrono::steady_clock;

SuiteRow evaluate_poses(const SuiteCell& cell, const Calibrator::Result& result, const MultiPoseSimulator& sim,
                        int asked, double seconds) {
  SuiteRow row = evaluate(cell, result, sim.T_lidar_camera(), seconds, "");
  const std::vector<int> moving = sim.moving_frames();
  int entered = 0;
  for (const PoseReport& pose : result.poses)
    for (int f : pose.frames) entered += std::count(moving.begin(), moving.end(), f) > 0;
  std::ostringstream scene;
  scene << "poses=" << asked << " drawn=" << std::min<std::size_t>(asked, sim.poses().size())
        << " found=" << result.poses.size() << " used=" << result.poses_used() << " moving_in_poses=" << entered;
  if (result.found)
    scene << " covered=" << std::max(0, row.covered)
          << " valid=" << result.joint.uncertainty.valid;
  row.scene = scene.str();
  return row;
}

/// Frame index after which the first `poses` static poses are complete.
int last_frame_of(const MultiPoseSimulator& sim, int poses) {
  int last = -1, seen = 0;
  for (const PoseSegment& s : sim.segments())
    if (s.pose_index >= 0 && seen++ < poses) last = s.first_frame + s.frames - 1;
  return last;
}

}  // namespace

std::vector<SuiteRow> run_poses_group(const SuiteGroup& group, const std::vector<SuiteCell>& cells, int threads,
                                      const std::function<void()>& on_frame) {
  MultiPoseConfig config;
  config.base = SimulationConfig::paper(group.setting, cells.empty() ? "vlp16" : cells.front().lidar);
  config.base.frames = kPoseFrames;
  config.base.noise_factor = group.noise_k;
  config.base.seed = group.seed;
  config.base.threads = threads;
  config.poses = kMostPoses;
  config.moving_frames = kMovingFrames;
  std::unique_ptr<MultiPoseSimulator> sim;
  std::string failure;
  try {
    sim = std::make_unique<MultiPoseSimulator>(config);
  } catch (const Error& error) {
    failure = std::string("simulation: ") + error.what();
  }
  std::vector<SuiteRow> rows;
  if (!sim) {
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
  std::vector<Calibrator> calibrators;
  std::vector<double> seconds(cells.size(), 0.0);
  for (const SuiteCell& cell : cells)
    calibrators.emplace_back(sim->cameras(), config.base.target, Calibrator::Params::preset(cell.preset));
  std::vector<std::vector<SuiteRow>> per_cell(cells.size());
  for (int i = 0; i < sim->frames(); ++i) {
    const SimulatedFrame frame = sim->frame(i);
    for (std::size_t c = 0; c < cells.size(); ++c) {
      const auto since = [](Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); };
      const auto start = Clock::now();
      calibrators[c].add(frame.lidar, frame.left, frame.right, std::to_string(i));
      seconds[c] += since(start);
      for (int p : {1, 2, 3, 5}) {
        // Fewer poses drawn than asked: the largest P is evaluated at the end.
        if (std::min(last_frame_of(*sim, p), sim->frames() - 1) != i) continue;
        const auto evaluated = Clock::now();
        const Calibrator::Result result = calibrators[c].result();
        seconds[c] += since(evaluated);
        per_cell[c].push_back(evaluate_poses(cells[c], result, *sim, p, seconds[c]));
      }
    }
    if (on_frame) on_frame();
  }
  for (int i = sim->frames(); i < group.frames && on_frame; ++i) on_frame();
  for (auto& cell_rows : per_cell) rows.insert(rows.end(), cell_rows.begin(), cell_rows.end());
  return rows;
}

}  // namespace l2s::sim::detail
