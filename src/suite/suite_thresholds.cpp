// The limits a suite run is held to (`l2s suite --quick --thresholds FILE`):
// per preset, a least success rate and greatest median errors per cell.

#include <l2s/sim/suite_results.hpp>

#include <l2s/error.hpp>

#include "io/yaml_helpers.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <tuple>

namespace l2s::sim {

namespace {

SuiteThresholds::PresetLimits read_preset_limits(const YAML::Node& presets, const std::string& where,
                                                 const std::string& path) {
  SuiteThresholds::PresetLimits out;
  for (const auto& entry : presets) {
    const auto name = entry.first.as<std::string>();
    const YAML::Node& node = entry.second;
    SuiteThresholds::Limits limits;
    limits.min_success_rate = io::yaml::read_double(node, "min_success_rate", path);
    limits.max_e_t = io::yaml::read_double(node, "max_e_t_mm", path) * 1e-3;
    limits.max_e_r = io::yaml::read_double(node, "max_e_r_deg", path) * M_PI / 180.0;
    if (limits.min_success_rate < 0.0 || limits.min_success_rate > 1.0)
      throw FileError(path, where + "." + name + ".min_success_rate must be 0..1");
    out.emplace_back(name, limits);
  }
  return out;
}

}  // namespace

SuiteThresholds read_suite_thresholds(const std::string& path) {
  const YAML::Node root = io::yaml::load_file(path);
  if (!io::yaml::has_key(root, "presets") || !root["presets"].IsMap())
    throw FileError(path, "expected a map 'presets: {name: {min_success_rate, max_e_t_mm, max_e_r_deg}}'");
  SuiteThresholds thresholds;
  thresholds.presets = read_preset_limits(root["presets"], "presets", path);
  if (io::yaml::has_key(root, "experiments")) {
    if (!root["experiments"].IsMap())
      throw FileError(path, "expected a map 'experiments: {experiment: {preset: {...}}}'");
    for (const auto& entry : root["experiments"]) {
      const auto experiment = entry.first.as<std::string>();
      if (!entry.second.IsMap()) throw FileError(path, "experiments." + experiment + " must be a map of presets");
      thresholds.experiments.emplace_back(
          experiment, read_preset_limits(entry.second, "experiments." + experiment, path));
    }
  }
  return thresholds;
}

std::vector<std::string> check_suite_thresholds(const std::vector<SuiteRow>& rows,
                                                const SuiteThresholds& thresholds) {
  // A cell variant: all repetitions of one (experiment, setting, lidar, K, preset).
  using Key = std::tuple<std::string, int, std::string, double, std::string>;
  std::map<Key, int> last_frames;
  const auto key_of = [](const SuiteRow& row) {
    const int setting = row.experiment == "scenes" ? 0 : row.setting;  // all scenes are one distribution
    return Key{row.experiment, setting, row.lidar, row.noise_k, row.preset};
  };
  for (const auto& row : rows) {
    int& last = last_frames[key_of(row)];
    last = std::max(last, row.frames);
  }
  std::map<Key, std::vector<const SuiteRow*>> variants;
  for (const auto& row : rows) {
    const Key key = key_of(row);
    if (row.frames == last_frames[key]) variants[key].push_back(&row);
  }

  std::vector<std::string> violations;
  for (const auto& [key, variant_rows] : variants) {
    const auto& [experiment, setting, lidar, k, preset] = key;
    const SuiteThresholds::PresetLimits* table = &thresholds.presets;
    for (const auto& [name, experiment_limits] : thresholds.experiments)
      if (name == experiment) table = &experiment_limits;
    const SuiteThresholds::Limits* limits = nullptr;
    for (const auto& [name, preset_limits] : *table)
      if (name == preset) limits = &preset_limits;
    if (!limits) continue;
    const SuiteStats stats = suite_stats(variant_rows);
    char where[160];
    std::snprintf(where, sizeof where, "%s setting %d %s K=%g %s (%d runs): ", experiment.c_str(), setting,
                  lidar.c_str(), k, preset.c_str(), stats.runs);
    char problem[160];
    if (stats.success_rate() < limits->min_success_rate) {
      std::snprintf(problem, sizeof problem, "success rate %.2f < %.2f", stats.success_rate(),
                    limits->min_success_rate);
      violations.push_back(where + std::string(problem));
    }
    if (stats.successes > 0 && stats.e_t_median > limits->max_e_t) {
      std::snprintf(problem, sizeof problem, "median e_t %.2f mm > %.2f mm", stats.e_t_median * 1e3,
                    limits->max_e_t * 1e3);
      violations.push_back(where + std::string(problem));
    }
    if (stats.successes > 0 && stats.e_r_median > limits->max_e_r) {
      std::snprintf(problem, sizeof problem, "median e_r %.3f deg > %.3f deg", stats.e_r_median * 180.0 / M_PI,
                    limits->max_e_r * 180.0 / M_PI);
      violations.push_back(where + std::string(problem));
    }
  }
  return violations;
}

}  // namespace l2s::sim
