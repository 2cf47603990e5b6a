#pragma once
// Fits the fan of a spinning lidar, one line v = t + h u per laser (see
// laser_line.hpp), to returns whose laser is unknown. Far returns fix the
// elevations, near ones the offsets, so the fit grows from far to near:
//  1. an offset profile h(t) from histogram sharpness (offset_profile.hpp);
//  2. first lasers from the far half of the returns, clustered by intercept;
//  3. then, until nothing changes: give each return to the laser whose line
//     predicts it within `gate` sigmas (a return whose prediction is still too
//     uncertain against the spacing of the lines waits for a later round);
//     refit each line (ridge least squares, prior h from the profile); returns
//     that no confident line explains become new lasers when they cluster;
//     adjacent lines that one line explains as well (BIC) merge; a line whose
//     residuals fall apart in two clumps splits.

#include "io/laser_line.hpp"
#include "io/line_index.hpp"
#include "io/offset_profile.hpp"

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
  int max_iterations = 12;
  std::size_t max_points = 16000;       ///< returns used for the fit (every k-th)
  ProfileParams profile;
};

/// The lasers found, ascending in t, and the profile they were fitted with.
struct Fan {
  std::vector<Line> lines;
  OffsetProfile profile;
  int iterations = 0;
};

Fan fit_fan(const std::vector<Point>& points, const FanParams& params);

/// Gives every point its nearest line, then refits, adds lines for clusters of
/// confident outliers (lasers too sparse for the fit's sample) and assigns
/// again. Returns each point's line (-1 when there are no lines).
std::vector<int> assign_all(const std::vector<Point>& points, Fan& fan, const FanParams& params);

}  // namespace l2s::io::fan
