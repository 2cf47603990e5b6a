// The scene check is judged by the truth it never sees: a good result should
// be ok, a result far off must never be. The classes are those of issue 11's
// acceptance (within 2 cm / 0.5 deg; beyond 10 cm or 2 deg).

#include "suite/suite_check_summary.hpp"

#include <array>
#include <cmath>
#include <map>
#include <string>

namespace l2s::sim::detail {
namespace {

constexpr double kGoodT = 0.02, kGoodR = 0.5 * M_PI / 180.0;
constexpr double kOffT = 0.10, kOffR = 2.0 * M_PI / 180.0;

const char* error_class(const SuiteRow& row) {
  if (row.e_t <= kGoodT && row.e_r <= kGoodR) return "within 2 cm and 0.5 deg";
  if (row.e_t > kOffT || row.e_r > kOffR) return "beyond 10 cm or 2 deg";
  return "in between";
}

}  // namespace

void write_check_summary(std::ostringstream& out, const std::vector<SuiteRow>& rows) {
  // Final evaluation of each cell only: a streaming cell's early frames would weigh more.
  std::map<std::string, const SuiteRow*> last;
  for (const SuiteRow& row : rows) {
    if (!row.success || row.verdict.empty()) continue;
    const SuiteRow*& kept = last[row.cell_key()];
    if (!kept || row.frames > kept->frames) kept = &row;
  }
  if (last.empty()) return;
  const std::array<const char*, 3> classes = {"within 2 cm and 0.5 deg", "in between", "beyond 10 cm or 2 deg"};
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
}

}  // namespace l2s::sim::detail
