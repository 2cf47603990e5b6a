// Statistics of the suite's runs, as the paper's box plots show them (median,
// quartiles), and summary.md: one table per experiment.

#include <l2s/sim/suite_results.hpp>

#include "suite/suite_check_summary.hpp"
#include "suite/suite_poses.hpp"
#include "suite/suite_scenes_summary.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <regex>
#include <sstream>
#include <tuple>

namespace l2s::sim {
namespace {

constexpr double kDeg = 180.0 / M_PI;

const char* title_of(const std::string& experiment) {
  if (experiment == "frames") return "frames: error against the number of frames (Fig. 5; VLP-16, K = 1)";
  if (experiment == "noise") return "noise: error against the noise factor K (Fig. 6; VLP-16, 30 frames)";
  if (experiment == "lidars") return "lidars: error per lidar model (Fig. 7; K = 1, 30 frames)";
  if (experiment == "quick") return "quick: CI smoke test (VLP-16, K = 1, 10 frames)";
  if (experiment == "scenes") return "scenes: randomised rigs, scenes and lidars (K = 1)";
  if (experiment == "poses") return "poses: error against the number of board poses (VLP-16, K = 1, 10 frames per pose)";
  if (experiment == "mono")
    return "mono: the left camera alone, by the board's markers, against the number of board poses (VLP-16, K = 1, "
           "10 frames per pose)";
  if (experiment == "lidar-pair")
    return "lidar-pair: VLP-16 to HDL-32E against the number of board poses (K = 1, 10 frames per pose)";
  return "";
}

std::string fixed(double value, int decimals) {
  if (std::isnan(value)) return "-";
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value);
  return buffer;
}

// Variant of a cell: everything but the setting and the repetition.
using Variant = std::tuple<std::string, double, std::string, int>;  // lidar, K, preset, frames

void table_header(std::ostringstream& out) {
  out << "| lidar | K | preset | frames | setting | runs | success | e_t median [mm] | e_t IQR [mm] | "
         "e_r median [deg] | e_r IQR [deg] |\n"
      << "|---|---|---|---|---|---|---|---|---|---|---|\n";
}

void table_row(std::ostringstream& out, const Variant& v, const std::string& setting,
               const std::vector<const SuiteRow*>& rows) {
  const SuiteStats s = suite_stats(rows);
  out << "| " << std::get<0>(v) << " | " << std::get<1>(v) << " | " << std::get<2>(v) << " | "
      << std::get<3>(v) << " | " << setting << " | " << s.runs << " | "
      << fixed(100.0 * s.success_rate(), 0) << " % | " << fixed(s.e_t_median * 1e3, 2) << " | "
      << fixed(s.e_t_iqr * 1e3, 2) << " | " << fixed(s.e_r_median * kDeg, 3) << " | "
      << fixed(s.e_r_iqr * kDeg, 3) << " |\n";
}

// Frame counts shown for the frames experiment's overall table.
bool shown_frame_count(int n, int last) {
  return n == 1 || n == 2 || n == 5 || n % 10 == 0 || n == last;
}

}  // namespace

double percentile(std::vector<double> values, double p) {
  if (values.empty()) return std::nan("");
  std::sort(values.begin(), values.end());
  const double position = std::clamp(p, 0.0, 100.0) / 100.0 * (values.size() - 1);
  const auto below = static_cast<std::size_t>(std::floor(position));
  const std::size_t above = std::min(below + 1, values.size() - 1);
  return values[below] + (position - below) * (values[above] - values[below]);
}

SuiteStats suite_stats(const std::vector<const SuiteRow*>& rows) {
  SuiteStats stats;
  std::vector<double> e_t, e_r;
  for (const SuiteRow* row : rows) {
    ++stats.runs;
    if (!row->success) continue;
    ++stats.successes;
    e_t.push_back(row->e_t);
    e_r.push_back(row->e_r);
  }
  stats.e_t_median = percentile(e_t, 50.0);
  stats.e_t_iqr = percentile(e_t, 75.0) - percentile(e_t, 25.0);
  stats.e_r_median = percentile(e_r, 50.0);
  stats.e_r_iqr = percentile(e_r, 75.0) - percentile(e_r, 25.0);
  return stats;
}

std::string suite_summary_markdown(const std::vector<SuiteRow>& all_rows) {
  std::vector<SuiteRow> rows = all_rows;
  sort_suite_rows(rows);
  std::vector<std::string> experiments;
  for (const auto& row : rows)
    if (std::find(experiments.begin(), experiments.end(), row.experiment) == experiments.end())
      experiments.push_back(row.experiment);

  std::ostringstream out;
  out << "# l2s suite summary\n\n"
      << "Simulated runs against exact ground truth. Success rate over all runs; median and "
         "interquartile range (IQR) of e_t and e_r over the successful ones (failures are counted, "
         "never dropped).\n";
  for (const auto& experiment : experiments) {
    if (experiment == "scenes" || is_pose_experiment(experiment)) {
      std::vector<const SuiteRow*> scene_rows;
      for (const auto& row : rows)
        if (row.experiment == experiment) scene_rows.push_back(&row);
      out << "\n## " << title_of(experiment) << "\n\n";
      if (experiment == "scenes")
        detail::write_scenes_summary(out, scene_rows);
      else
        detail::write_poses_summary(out, experiment, scene_rows);
      continue;
    }
    int last = 0;
    for (const auto& row : rows)
      if (row.experiment == experiment) last = std::max(last, row.frames);
    // Per variant and setting, the final evaluations; per variant and frame count, all settings.
    std::map<Variant, std::map<int, std::vector<const SuiteRow*>>> by_setting;
    std::map<Variant, std::vector<const SuiteRow*>> overall;
    std::map<std::string, int> reasons;
    for (const auto& row : rows) {
      if (row.experiment != experiment) continue;
      const Variant variant{row.lidar, row.noise_k, row.preset, row.frames};
      if (experiment != "frames" || shown_frame_count(row.frames, last)) overall[variant].push_back(&row);
      if (experiment == "frames" && row.frames != last) continue;
      by_setting[variant][row.setting].push_back(&row);
      // Frame counts inside reasons would make every reason unique.
      if (!row.success) ++reasons[std::regex_replace(row.reason, std::regex("[0-9]+"), "#")];
    }

    out << "\n## " << title_of(experiment) << "\n\n";
    if (experiment == "frames") {
      out << "All settings, after each number of frames:\n\n";
      table_header(out);
      // Ordered by preset, then frames.
      std::vector<Variant> variants;
      for (const auto& [variant, unused] : overall) variants.push_back(variant);
      std::stable_sort(variants.begin(), variants.end(), [](const Variant& a, const Variant& b) {
        return std::tie(std::get<2>(a), std::get<3>(a)) < std::tie(std::get<2>(b), std::get<3>(b));
      });
      for (const auto& variant : variants) table_row(out, variant, "all", overall[variant]);
      out << "\nPer setting, after " << last << " frames:\n\n";
    }
    table_header(out);
    for (const auto& [variant, settings] : by_setting) {
      for (const auto& [setting, cell_rows] : settings) table_row(out, variant, std::to_string(setting), cell_rows);
      table_row(out, variant, "**all**", overall[variant]);
    }
    if (!reasons.empty()) {
      out << "\nFailures (final evaluations; # stands for a number):\n\n";
      for (const auto& [reason, count] : reasons) out << "- " << count << " x " << reason << "\n";
    }
  }
  detail::write_check_summary(out, rows);
  return out.str();
}

}  // namespace l2s::sim
