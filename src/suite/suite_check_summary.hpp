#pragma once
// summary.md's section on the scene check (issue 11): how its verdicts sort
// the results by their true error (see suite_check_summary.cpp).

#include <l2s/sim/suite_results.hpp>

#include <sstream>
#include <vector>

namespace l2s::sim::detail {

/// Within 2 cm and 0.5 deg of the truth: what the acceptance calls a good
/// result (false without errors).
bool within_acceptance(const SuiteRow& row);

/// Final evaluations with a verdict, per class of true error (good: within
/// 2 cm and 0.5 deg; off: beyond 10 cm or 2 deg; between): how many got
/// ok, suspect, failed. Writes nothing when no row has a verdict.
void write_check_summary(std::ostringstream& out, const std::vector<SuiteRow>& rows);

}  // namespace l2s::sim::detail
