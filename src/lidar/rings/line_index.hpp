#pragma once
// Finding the laser line nearest to a return, the search that ring recovery
// runs once per return (and several times per return of its fit sample).

#include "lidar/rings/laser_line.hpp"

#include <cstdint>
#include <vector>

namespace l2s::io::fan {

/// A return's nearest line and its residual.
struct Match {
  int line = -1;          ///< -1 when there are no lines
  double residual = 0.0;  ///< v - prediction, v units
};

/// Lines sorted by t, packed for the search.
class LineIndex {
 public:
  /// With `lookup`, also builds a table that answers most searches with one
  /// load (worth it for a whole sweep, not for a few thousand returns).
  explicit LineIndex(const std::vector<Line>& lines, bool lookup = false);

  /// The line with the smallest |v - prediction| at p.u.
  Match nearest(const Point& p) const;

 private:
  Match bisect(const Point& p) const;
  Match best_around(const Point& p, std::size_t center, std::size_t reach) const;
  void build_lookup();

  std::vector<double> t_, h_;
  // Lookup table: for u-bins of width kBinU, the nearest line at the bin's
  // centre for v-cells of width cell_v_ from cell_v0_[bin] on.
  double cell_v_ = 0.0;
  std::vector<double> cell_v0_;
  std::vector<std::uint32_t> cell_begin_;  // first cell of each bin in cells_
  std::vector<std::uint16_t> cells_;
};

}  // namespace l2s::io::fan
