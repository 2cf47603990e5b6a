#pragma once
// Fits the fan of a spinning lidar, one line v = t + h u per laser (see
// laser_line.hpp), to returns whose laser is unknown. Far returns fix the
// elevations, near ones the offsets, so the fit grows from far to near:
//  1. an offset profile h(t) from histogram sharpness (offset_profile.hpp);
//  2. returns in chunks of distance, far first (a chunk is narrow enough in
//     u for the lines fitted so far to predict it): a return joins the one
//     line that explains it within `gate` sigmas of its prediction (the
//     prediction's own uncertainty included); returns several lines could
//     explain wait for a later chunk; returns no line explains group by
//     intercept into new lasers (fan_grouping.hpp), with a prior on h from the
//     established neighbours (fan_state.hpp); a line grown much wider than a
//     laser is split again;
//  3. tidying (fan_cleanup.hpp): refit under the finished prior, merge
//     duplicates, dissolve strays and lines that cross, reassign all returns.
// assign_all then gives every return of the sweep its nearest line.

#include "lidar/rings/laser_line.hpp"
#include "lidar/rings/line_index.hpp"
#include "lidar/rings/offset_profile.hpp"

#include <cstddef>
#include <vector>

namespace l2s::io::fan {

struct FanParams {
  double min_gap = 0.1 * M_PI / 180.0;  ///< [rad] two lasers are at least this far apart
  std::size_t min_points = 3;           ///< returns a laser needs
  double offset_sigma = 0.01;           ///< [m] spread of a laser's h about the profile
  double noise = 0.0004;                ///< [rad] expected elevation noise of a return
  double noise_floor = 0.0002;          ///< [rad] smallest residual scale of a laser
  double gate = 4.0;                    ///< sigmas within which a return belongs to a line
  double new_line_range = 0.5;          ///< [m] nearer returns never start a laser of their own
  double crossing_range = 2.0;          ///< [m] two lasers' lines never cross beyond this
  std::size_t max_points = 16000;       ///< returns used for the fit (every k-th)
  ProfileParams profile;
};

/// The lasers found, ascending in t, and the profile they were fitted with.
struct Fan {
  std::vector<Line> lines;
  OffsetProfile profile;
  int chunks = 0;  ///< distance chunks the fit grew through
};

Fan fit_fan(const std::vector<Point>& points, const FanParams& params);

/// Gives every return its nearest line; returns that no line explains, when
/// they group (a laser too sparse to show in the fit's sample), become lines
/// and every return is assigned again. Returns each return's line (-1 when
/// there are no lines).
std::vector<int> assign_all(const std::vector<Point>& points, Fan& fan, const FanParams& params);

}  // namespace l2s::io::fan
