// The cells of the paper's experiments (Sec. IV-B): Fig. 5 error against the
// number of frames, Fig. 6 noise factors, Fig. 7 lidar models; each cell
// repeated with seeds derived from its coordinates.

#include <l2s/sim/suite.hpp>

#include <l2s/error.hpp>

#include "sim/random.hpp"
#include "suite/suite_poses.hpp"

#include <cmath>
#include <limits>
#include <sstream>

namespace l2s::sim {
namespace {

constexpr int kSettings = 9;

struct ExperimentSpec {
  std::vector<int> settings;
  std::vector<std::string> lidars;
  std::vector<double> noise_factors;
  int frames = 30;
  bool every_frame = false;
};

ExperimentSpec spec_of(const std::string& experiment, const SuiteOptions& options) {
  std::vector<int> all_settings;
  for (int s = 1; s <= kSettings; ++s) all_settings.push_back(s);
  if (experiment == "frames") return {all_settings, {"vlp16"}, {1.0}, 40, true};
  if (experiment == "noise") return {all_settings, {"vlp16"}, {0.0, 1.0, 2.0, 3.0}, 30, false};
  if (experiment == "lidars") return {all_settings, {"vlp16", "hdl32", "hdl64"}, {1.0}, 30, false};
  // Quick: a simple, a rotated and the hardest setting of Table I.
  if (experiment == "quick") return {{1, 3, 8}, {"vlp16"}, {1.0}, 10, false};
  // Pose experiments: one recording of five poses per setting (its frames: all of them).
  if (is_pose_experiment(experiment))
    return {all_settings, {"vlp16"}, {1.0}, detail::pose_recording_frames(detail::kMostPoses), false};
  if (experiment == "scenes") {
    std::vector<int> scenes;
    for (int s = 1; s <= options.scene_count; ++s) scenes.push_back(s);
    return {scenes, {"random"}, {1.0}, options.scene_frames, false};
  }
  throw ParamError("experiment", "unknown experiment '" + experiment +
                                     "' (frames, noise, lidars, scenes, poses, mono, lidar-pair or quick)");
}

// FNV-1a: a stable hash of a name (std::hash is not specified across platforms).
std::uint64_t hash_name(const std::string& name) {
  std::uint64_t h = 0xCBF29CE484222325ULL;
  for (const unsigned char c : name) h = (h ^ c) * 0x100000001B3ULL;
  return h;
}

std::string format_k(double k) {
  std::ostringstream out;
  out << k;
  return out.str();
}

}  // namespace

void SuiteOptions::validate() const {
  if (experiments.empty()) throw ParamError("experiment", "at least one experiment");
  if (scene_count < 1 || scene_count > 100000) throw ParamError("count", "scenes must be 1..100000");
  if (scene_frames < 1 || scene_frames > 10000) throw ParamError("scene_frames", "must be 1..10000");
  for (const auto& experiment : experiments) spec_of(experiment, *this);
  if (presets.empty()) throw ParamError("preset", "at least one preset");
  for (const auto& preset : presets) {
    if (preset != "default" && preset != "paper" && preset != "mono")
      throw ParamError("preset", "unknown preset '" + preset + "' (default, paper or mono)");
    if (preset == "mono" && (experiments.size() != 1 || experiments.front() != "scenes"))
      throw ParamError("preset", "mono runs on the scenes experiment alone (its boards may carry markers)");
  }
  if (repeats < 1 || repeats > 10000) throw ParamError("repeats", "must be 1..10000");
}

namespace {

// One spelling of a cell's identity, for cells and for the rows they produce.
template <class CellOrRow>
std::string key_of(const CellOrRow& c) {
  return c.experiment + "/" + std::to_string(c.setting) + "/" + c.lidar + "/" + format_k(c.noise_k) + "/" +
         c.preset + "/" + std::to_string(c.repetition);
}

}  // namespace

std::string SuiteCell::key() const { return key_of(*this); }

std::string SuiteRow::cell_key() const { return key_of(*this); }

SuiteRow SuiteRow::of(const SuiteCell& cell) {
  SuiteRow row;
  row.experiment = cell.experiment;
  row.setting = cell.setting;
  row.lidar = cell.lidar;
  row.noise_k = cell.noise_k;
  row.frames = cell.frames;
  row.preset = cell.preset;
  row.seed = cell.seed;
  row.repetition = cell.repetition;
  row.e_t = row.e_r = std::numeric_limits<double>::quiet_NaN();
  return row;
}

std::uint64_t suite_seed(std::uint64_t base_seed, const std::string& experiment, int setting,
                         double noise_k, int repetition) {
  const auto k_milli = static_cast<std::uint64_t>(std::llround(noise_k * 1000.0));
  const std::uint64_t h = detail::hash_counters(base_seed, hash_name(experiment),
                                                static_cast<std::uint64_t>(setting), k_milli,
                                                static_cast<std::uint64_t>(repetition));
  // 31 bits: short enough to read and retype into `l2s simulate --seed`.
  return h >> 33;
}

std::vector<SuiteGroup> make_suite_plan(const SuiteOptions& options) {
  options.validate();
  std::vector<SuiteGroup> plan;
  for (const auto& experiment : options.experiments) {
    const ExperimentSpec spec = spec_of(experiment, options);
    for (const double k : spec.noise_factors)
      for (const int setting : spec.settings)
        // A scene is its own draw: more scenes, not repetitions, give more runs.
        for (int repetition = 0; repetition < (experiment == "scenes" ? 1 : options.repeats); ++repetition) {
          SuiteGroup group;
          group.experiment = experiment;
          group.setting = setting;
          group.noise_k = k;
          group.frames = spec.frames;
          group.repetition = repetition;
          group.seed = suite_seed(options.seed, experiment, setting, k, repetition);
          group.boards = options.scene_boards;
          for (const auto& lidar : spec.lidars)
            for (const auto& preset : options.presets)
              group.cells.push_back({experiment, setting, lidar, k, spec.frames, preset, repetition,
                                     group.seed, spec.every_frame});
          plan.push_back(std::move(group));
        }
  }
  return plan;
}

}  // namespace l2s::sim
