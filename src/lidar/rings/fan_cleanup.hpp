#pragma once
// Tidying the fan once it has grown (laser_fan.hpp): refit under the finished
// prior, merge duplicates, dissolve strays and lines that cross, and give all
// returns again to the lines.

#include "lidar/rings/fan_state.hpp"

#include <cstddef>
#include <vector>

namespace l2s::io::fan {

/// Merges adjacent lines that are one laser; returns how many merges.
std::size_t merge_lines(std::vector<Fitted>& lines, const OffsetProfile& profile,
                        const FanParams& params);
/// Refits every line under the prior of the finished fan.
void refit_all(std::vector<Fitted>& lines, const OffsetProfile& profile, const FanParams& params);
/// Gives every return again to the line that alone explains it and refits.
void reassign(const std::vector<Point>& points, std::vector<Fitted>& lines,
              const OffsetProfile& profile, const FanParams& params);
/// Dissolves the weaker of two adjacent lines that cross beyond crossing_range.
std::size_t dissolve_crossing(std::vector<Fitted>& lines, const FanParams& params);
/// Dissolves lines with a handful of returns among lines with hundreds.
std::size_t dissolve_strays(std::vector<Fitted>& lines);

}  // namespace l2s::io::fan
