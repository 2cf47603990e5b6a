// One-dimensional peak search for the calibration check. The score is a sum
// of narrow kernels, and lidar rings make it repeat (a vertical image edge
// stays on itself when shifted vertically), so the highest sample may be a
// side lobe: the peak that describes the checked transform is the one
// reached by climbing from zero. A coarse scan finds it and the best one, a
// fine scan and a parabola place it, the coarse samples give its width
// against the background.

#include "check/peak_scan.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace l2s::detail {
namespace {

/// Distance from sample `best` to where the samples first fall to `level`
/// in direction `dir` (linear interpolation); the scan's end when never.
double half_width(const std::vector<double>& values, int best, int dir, double level, double step) {
  for (int i = best + dir; i >= 0 && i < static_cast<int>(values.size()); i += dir)
    if (values[i] <= level) {
      const double above = values[i - dir] - level, below = level - values[i];
      return (std::abs(i - best) - 1 + above / std::max(above + below, 1e-12)) * step;
    }
  return dir > 0 ? (values.size() - 1 - best) * step : best * step;
}

/// The local maximum reached from `start` by stepping to the higher
/// neighbour while the score rises.
int climb(const std::vector<double>& values, int start) {
  int i = start;
  for (;;) {
    const double left = i > 0 ? values[i - 1] : -1.0;
    const double right = i + 1 < static_cast<int>(values.size()) ? values[i + 1] : -1.0;
    if (left <= values[i] && right <= values[i]) return i;
    i += right > left ? 1 : -1;
  }
}

/// Refines the peak near `centre` with samples every `fine`, then a parabola.
double refine(const std::function<double(double)>& score, double centre, double centre_value, double fine,
              double& value) {
  double best = centre;
  value = centre_value;
  for (int k = -4; k <= 4; ++k) {
    if (k == 0) continue;
    const double v = score(centre + k * fine);
    if (v > value) value = v, best = centre + k * fine;
  }
  const double left = score(best - fine), right = score(best + fine);
  const double curvature = left + right - 2.0 * value;
  return best + (curvature < 0.0 ? 0.5 * fine * (left - right) / curvature : 0.0);
}

}  // namespace

ScanPeak scan_peak(const std::function<double(double)>& score, double step, double range) {
  const int n = std::max(1, static_cast<int>(std::ceil(range / step)));
  std::vector<double> coarse(2 * n + 1);
  for (int i = -n; i <= n; ++i) coarse[i + n] = score(i * step);
  const int local = climb(coarse, n);
  const int best = static_cast<int>(std::max_element(coarse.begin(), coarse.end()) - coarse.begin());

  std::vector<double> sorted = coarse;
  std::nth_element(sorted.begin(), sorted.begin() + n, sorted.end());
  const double background = sorted[n];
  ScanPeak peak;
  const double level = 0.5 * (coarse[local] + background);
  peak.width = coarse[local] > background
                   ? 0.5 * (half_width(coarse, local, -1, level, step) + half_width(coarse, local, 1, level, step))
                   : range;
  peak.prominence = coarse[local] > 0.0 ? (coarse[local] - background) / coarse[local] : 0.0;
  peak.offset = refine(score, (local - n) * step, coarse[local], step / 4.0, peak.value);
  peak.best_offset = (best - n) * step;
  peak.best_value = std::max(coarse[best], peak.value);
  if (peak.value >= coarse[best]) peak.best_offset = peak.offset;
  return peak;
}

}  // namespace l2s::detail
