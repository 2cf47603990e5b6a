#pragma once
// New lasers from returns no line explains: grouping returns by intercept
// (and splitting groups where two lasers touch), for new lines and for lines
// that took two lasers' returns.

#include "lidar/rings/fan_state.hpp"

#include <cstddef>
#include <utility>
#include <vector>

namespace l2s::io::fan {

/// (intercept, return index) pairs, sorted by intercept.
using Run = std::vector<std::pair<double, std::size_t>>;

/// Groups of a sorted run whose intercepts follow each other within the
/// minimum gap, split further where two lasers touch (a valley in the run's
/// density); groups smaller than min_points are left out.
std::vector<std::vector<std::size_t>> groups_of(const Run& sorted, const FanParams& params);

/// Groups of `members` by their intercepts, each taken under the offset of the
/// line nearest to it (or under the profile while there are no lines).
std::vector<std::vector<std::size_t>> cluster(const std::vector<Point>& points,
                                              const std::vector<std::size_t>& members,
                                              const std::vector<Line>& lines,
                                              const OffsetProfile& profile,
                                              const FanParams& params);

/// Candidates beyond min_range [m] that group become new lines (a few returns
/// each, more in a cloud whose lines hold many). Returns the other candidates.
std::vector<std::size_t> add_new_lines(const std::vector<Point>& points,
                                       const std::vector<std::size_t>& candidates,
                                       std::vector<Fitted>& lines, const OffsetProfile& profile,
                                       const FanParams& params, double min_range);

/// Splits lines whose residuals spread far wider than a laser's; returns how many.
std::size_t split_wide_lines(const std::vector<Point>& points, std::vector<Fitted>& lines,
                             const OffsetProfile& profile, const FanParams& params);

}  // namespace l2s::io::fan
