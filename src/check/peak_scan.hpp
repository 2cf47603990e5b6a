#pragma once
// A score scanned along one degree of freedom around zero (private to the
// library): the peak the checked transform sits on, and the best one.

#include <functional>

namespace l2s::detail {

struct ScanPeak {
  double offset = 0.0;      ///< the local peak reached by climbing from zero (parabola through the finest samples)
  double value = 0.0;       ///< the score there
  double width = 0.0;       ///< its half width at half height above the scan's median; the scan's reach when it never falls that low
  double prominence = 0.0;  ///< (value - median) / value, 0 when the score is flat or zero
  double best_offset = 0.0; ///< the highest sample of the whole scan
  double best_value = 0.0;  ///< and its score
};

/// Samples `score` every `step` over [-range, range], climbs from zero to
/// the nearest local peak, then samples every step / 4 within one step of it.
ScanPeak scan_peak(const std::function<double(double)>& score, double step, double range);

}  // namespace l2s::detail
