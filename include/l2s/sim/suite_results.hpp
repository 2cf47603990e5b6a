#pragma once
// What `l2s suite` keeps: results.csv (one line per evaluation, appended as
// cells finish, read back to resume), the statistics of the paper's box plots
// (median, IQR), summary.md, and the thresholds that `--quick` is held to.

#include <l2s/sim/suite.hpp>

#include <set>
#include <string>
#include <vector>

namespace l2s::sim {

/// The header line of results.csv (no newline).
std::string suite_csv_header();
/// One row as a CSV line (no newline); text fields quoted when needed.
std::string to_csv_line(const SuiteRow& row);
/// Parses a line written by to_csv_line; throws Error on a malformed line.
SuiteRow parse_csv_line(const std::string& line);

/// results.csv as read back: complete lines only.
struct SuiteCsv {
  std::vector<SuiteRow> rows;
  bool trimmed = false;  ///< a last line without newline (an interrupted write) was dropped
};
/// Reads results.csv; a missing file gives no rows. Throws FileError on a bad
/// header or a malformed complete line.
SuiteCsv read_suite_csv(const std::string& path);
/// Writes header and rows atomically (temporary file, then rename).
void write_suite_csv(const std::string& path, const std::vector<SuiteRow>& rows);

/// What a resumed run keeps and skips.
struct SuiteResume {
  std::vector<SuiteRow> kept;         ///< rows of complete cells (and of cells not in the plan)
  std::set<std::string> done;         ///< keys of complete cells of the plan
  std::size_t dropped = 0;            ///< rows of incomplete cells, to be run again
};
/// Splits earlier rows into finished cells and leftovers. Throws Error when a
/// row's seed differs from the plan's (results.csv of another --seed).
SuiteResume resume_suite(const std::vector<SuiteGroup>& plan, const std::vector<SuiteRow>& rows);

/// Sorts rows in a stable reading order (experiment, setting, lidar, K,
/// preset, repetition, frames), so the final file does not depend on --jobs.
void sort_suite_rows(std::vector<SuiteRow>& rows);

/// Percentile with linear interpolation between order statistics (numpy's
/// default), p in [0, 100]; NaN for no values.
double percentile(std::vector<double> values, double p);

/// Statistics of a set of runs.
struct SuiteStats {
  int runs = 0;
  int successes = 0;
  double e_t_median = 0.0, e_t_iqr = 0.0;  ///< [m] over successful runs (NaN when none)
  double e_r_median = 0.0, e_r_iqr = 0.0;  ///< [rad]
  double success_rate() const { return runs > 0 ? static_cast<double>(successes) / runs : 0.0; }
};
SuiteStats suite_stats(const std::vector<const SuiteRow*>& rows);

/// summary.md: per experiment, a table of success rate, median and IQR of e_t
/// [mm] and e_r [deg] per setting and overall, then the failure reasons.
std::string suite_summary_markdown(const std::vector<SuiteRow>& rows);

/// Limits a run is held to (tests/suite_quick_thresholds.yaml).
struct SuiteThresholds {
  struct Limits {
    double min_success_rate = 1.0;  ///< per cell variant, over repetitions
    double max_e_t = 0.0;           ///< [m] median over successful repetitions
    double max_e_r = 0.0;           ///< [rad]
  };
  using PresetLimits = std::vector<std::pair<std::string, Limits>>;  ///< preset name -> limits
  PresetLimits presets;
  /// Limits of one experiment that replace `presets` for it (experiment -> preset -> limits).
  std::vector<std::pair<std::string, PresetLimits>> experiments;
};
/// Reads `presets: {name: {min_success_rate, max_e_t_mm, max_e_r_deg}}` and the
/// optional `experiments: {experiment: {name: {...}}}`; throws FileError.
SuiteThresholds read_suite_thresholds(const std::string& path);
/// One line per cell variant (experiment, setting, lidar, K, preset, final
/// frame count) that breaks its preset's limits; empty when all pass. The
/// scenes of "scenes" are one variant: their limits hold for the distribution.
std::vector<std::string> check_suite_thresholds(const std::vector<SuiteRow>& rows,
                                                const SuiteThresholds& thresholds);

}  // namespace l2s::sim
