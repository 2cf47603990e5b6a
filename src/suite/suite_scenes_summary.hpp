#pragma once
// summary.md's section for the "scenes" experiment (see suite_stats.cpp).

#include <l2s/sim/suite_results.hpp>

#include <sstream>
#include <vector>

namespace l2s::sim::detail {

/// Per preset: scenes, success rate, median / p95 / max of e_t and e_r; then every failure with its scene.
void write_scenes_summary(std::ostringstream& out, const std::vector<const SuiteRow*>& rows);

}  // namespace l2s::sim::detail
