// The scene check is judged by the truth it never sees: a good result should
// be ok, a result far off must never be. The classes are those of issue 11's
// acceptance (within 2 cm / 0.5 deg; beyond 10 cm or 2 deg).

#include "suite/suite_check_summary.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <regex>
#include <string>

namespace l2s::sim::detail {
namespace {

constexpr double kGoodT = 0.02, kGoodR = 0.5 * M_PI / 180.0;
constexpr double kOffT = 0.10, kOffR = 2.0 * M_PI / 180.0;

constexpr const char* kGood = "within 2 cm and 0.5 deg";
constexpr const char* kOff = "beyond 10 cm or 2 deg";

const char* error_class(const SuiteRow& row) {
  if (within_acceptance(row)) return kGood;
  if (row.e_t > kOffT || row.e_r > kOffR) return kOff;
  return "in between";
}

/// Why good results were not ok: each reason once, its numbers hidden so
/// that the same rule met by several results counts together.
void write_false_alarms(std::ostringstream& out, const std::map<std::string, const SuiteRow*>& last) {
  std::map<std::string, int> reasons;
  for (const auto& [key, row] : last) {
    if (std::string(error_class(*row)) != kGood || row->verdict == "ok") continue;
    const std::string& list = row->check_reasons;
    for (std::size_t start = 0; start < list.size();) {
      const std::size_t end = std::min(list.find(" | ", start), list.size());
      const std::string reason = list.substr(start, end - start);
      if (!reason.empty()) ++reasons[std::regex_replace(reason, std::regex("[+-]?[0-9]+(\\.[0-9]+)?"), "#")];
      start = end + 3;
    }
  }
  if (reasons.empty()) return;
  out << "\nWhy results within 2 cm and 0.5 deg were not ok (a result may have several reasons):\n\n";
  for (const auto& [reason, count] : reasons) out << "- " << count << " x " << reason << "\n";
}

/// Results far off that the check let through: the failure it exists to prevent.
void write_missed_errors(std::ostringstream& out, const std::map<std::string, const SuiteRow*>& last) {
  std::ostringstream list;
  for (const auto& [key, row] : last)
    if (std::string(error_class(*row)) == kOff && row->verdict == "ok")
      list << "- " << key << ": " << row->e_t * 1e3 << " mm, " << row->e_r * 180.0 / M_PI << " deg"
           << (row->scene.empty() ? "" : " (" + row->scene + ")") << "\n";
  if (list.str().empty()) return;
  out << "\nResults beyond 10 cm or 2 deg that the check called ok:\n\n" << list.str();
}

}  // namespace

bool within_acceptance(const SuiteRow& row) { return row.e_t <= kGoodT && row.e_r <= kGoodR; }

void write_check_summary(std::ostringstream& out, const std::vector<SuiteRow>& rows) {
  // Final evaluation of each cell only: a streaming cell's early frames would weigh more.
  std::map<std::string, const SuiteRow*> last;
  for (const SuiteRow& row : rows) {
    if (!row.success || row.verdict.empty()) continue;
    const SuiteRow*& kept = last[row.cell_key()];
    if (!kept || row.frames > kept->frames) kept = &row;
  }
  if (last.empty()) return;
  const std::array<const char*, 3> classes = {kGood, "in between", kOff};
  std::map<std::string, std::map<std::string, int>> counts;  // class -> verdict -> runs
  for (const auto& [key, row] : last) ++counts[error_class(*row)][row->verdict];

  out << "\n## The scene check against the truth\n\n"
      << "Verdicts of the calibrations that gave a transform (final evaluations), by their true error.\n\n"
      << "| true error | results | ok | suspect | failed |\n|---|---|---|---|---|\n";
  for (const char* name : classes) {
    auto& verdicts = counts[name];
    const int total = verdicts["ok"] + verdicts["suspect"] + verdicts["failed"];
    out << "| " << name << " | " << total << " | " << verdicts["ok"] << " | " << verdicts["suspect"] << " | "
        << verdicts["failed"] << " |\n";
  }
  write_false_alarms(out, last);
  write_missed_errors(out, last);
}

}  // namespace l2s::sim::detail
