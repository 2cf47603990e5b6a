// The "poses" section of summary.md (issue 9): per number of poses P, the
// success rate and error statistics over the settings, whether P = 3 beats
// P = 1 on the same recordings, the coverage of the stated 95 % uncertainty
// (per DoF, and of all six at once) and the moving frames that entered a pose.

#include "suite/suite_poses.hpp"

#include <l2s/sim/suite_results.hpp>

#include <cmath>
#include <cstdio>
#include <map>
#include <regex>
#include <string>

namespace l2s::sim::detail {
namespace {

/// An integer field "name=value" of a row's scene record, or -1.
int field(const SuiteRow& row, const std::string& name) {
  std::smatch match;
  if (!std::regex_search(row.scene, match, std::regex(name + "=([0-9]+)"))) return -1;
  return std::stoi(match[1]);
}

std::string fixed(const char* pattern, double value) {
  if (std::isnan(value)) return "-";
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, pattern, value);
  return buffer;
}

struct PerP {
  int runs = 0, successes = 0, covered_dofs = 0, covered_runs = 0, valid = 0, entered = 0, used = 0;
  std::vector<double> e_t, e_r;
};

}  // namespace

void write_poses_summary(std::ostringstream& out, const std::string& experiment,
                         const std::vector<const SuiteRow*>& rows) {
  std::map<std::string, std::map<int, PerP>> stats;  // preset -> P -> stats
  std::map<std::string, std::map<std::string, std::map<int, double>>> e_r_of;  // preset -> run -> P -> e_r
  for (const SuiteRow* row : rows) {
    const int p = field(*row, "poses");
    PerP& s = stats[row->preset][p];
    ++s.runs;
    s.entered += std::max(0, field(*row, "moving_in_poses"));
    if (!row->success) continue;
    ++s.successes;
    s.used += std::max(0, field(*row, "used"));
    s.e_t.push_back(row->e_t * 1e3);
    s.e_r.push_back(row->e_r * 180.0 / M_PI);
    if (field(*row, "valid") == 1) {
      ++s.valid;
      const int covered = field(*row, "covered");
      s.covered_dofs += covered;
      s.covered_runs += covered == 6;
    }
    e_r_of[row->preset][std::to_string(row->setting) + "/" + std::to_string(row->repetition)][p] = row->e_r;
  }
  const char* sensors = experiment == "mono"         ? "VLP-16 and the left camera, the board's markers"
                        : experiment == "lidar-pair" ? "VLP-16 and HDL-32E"
                                                     : "VLP-16 and the stereo rig";
  out << "One recording per setting and repetition: " << kMostPoses << " board poses of " << kPoseFrames
      << " frames, " << kMovingFrames << " moving frames between poses (" << sensors << "). Each P is evaluated on the "
      << "first P poses of the same recording. Coverage: the true error within the stated 95 % bound, per "
         "DoF and for all six DoF of a run at once.\n\n"
      << "| preset | P | runs | success | poses used (mean) | e_t median [mm] | e_t p90 [mm] | e_r median [deg] | "
         "e_r p90 [deg] | 95 % covers, per DoF | all 6 DoF | moving frames in a pose |\n"
      << "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& [preset, by_p] : stats)
    for (const auto& [p, s] : by_p) {
      out << "| " << preset << " | " << p << " | " << s.runs << " | "
          << fixed("%.0f %%", 100.0 * s.successes / std::max(1, s.runs)) << " | "
          << fixed("%.2f", static_cast<double>(s.used) / std::max(1, s.successes)) << " | "
          << fixed("%.2f", percentile(s.e_t, 50)) << " | " << fixed("%.2f", percentile(s.e_t, 90)) << " | "
          << fixed("%.3f", percentile(s.e_r, 50)) << " | " << fixed("%.3f", percentile(s.e_r, 90)) << " | "
          << fixed("%.0f %%", 100.0 * s.covered_dofs / std::max(1, 6 * s.valid)) << " | "
          << fixed("%.0f %%", 100.0 * s.covered_runs / std::max(1, s.valid)) << " | " << s.entered << " |\n";
    }
  for (const auto& [preset, runs] : e_r_of) {
    int better = 0, both = 0;
    for (const auto& [run, by_p] : runs)
      if (by_p.count(1) && by_p.count(3)) ++both, better += by_p.at(3) < by_p.at(1);
    out << "\n" << preset << ": P = 3 has a smaller e_r than P = 1 in " << better << " of " << both
        << " recordings.\n";
  }
}

}  // namespace l2s::sim::detail
