#pragma once
// The vertical origin offset expected for a laser of a given elevation. The
// lasers of one sensor share offsets that change smoothly across the fan (one
// lens, one block of lasers; HDL-64E: ~0.21 m for the upper block, ~0.15 m for
// the lower), so a profile measured from the cloud itself predicts a laser's h
// before its own returns pin it down (a laser seen at one distance only).
//
// Measured without knowing which return belongs to which laser: for a trial h,
// the returns' intercepts t = v - h u pile up into sharp peaks (one per laser)
// only when h is right; the sharpest histogram wins, first for the whole fan,
// then band by band of elevation.

#include "lidar/rings/laser_line.hpp"

#include <utility>
#include <vector>

namespace l2s::io::fan {

struct ProfileParams {
  double offset_range = 0.5;      ///< [m] |h| searched for the whole fan
  double band_range = 0.12;       ///< [m] a band's h is searched this far from the fan's
  double band_width = 0.03;       ///< tangent units (~1.7 deg) of one band
  double bin = 0.0005;            ///< tangent units (~0.03 deg) of one histogram bin
  std::size_t max_points = 3000;  ///< returns used (every k-th), for speed
};

class OffsetProfile {
 public:
  OffsetProfile() = default;
  /// A profile that is `h` everywhere.
  explicit OffsetProfile(double h) : global_(h) {}
  /// Measures the profile from returns in model coordinates.
  static OffsetProfile estimate(const std::vector<Point>& points, const ProfileParams& params);

  /// [m] expected h of a laser at tangent t (linear between band centres).
  double at(double t) const;
  /// [m] the offsets of the bands either side of t, lower band first (equal
  /// beyond the ends and without bands): where they differ much, t lies on a
  /// jump between blocks of lasers (HDL-64E), and a laser there has the one or
  /// the other offset, not the average.
  std::pair<double, double> sides(double t) const;
  /// The intercept t of a return under the profile (t = v - at(t) u, solved
  /// by fixed-point steps: the profile changes slowly with t).
  double intercept(const Point& p) const;
  double global() const { return global_; }  ///< [m] the whole fan's sharpest h

 private:
  double global_ = 0.0;
  std::vector<double> centers_;  // band centres, tangent units, ascending
  std::vector<double> offsets_;  // [m] h of each band
};

}  // namespace l2s::io::fan
