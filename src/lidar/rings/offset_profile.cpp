// Offset profile by histogram sharpness (see offset_profile.hpp).
#include "lidar/rings/offset_profile.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace l2s::io::fan {
namespace {

constexpr double kMaxU = 2.0;         // [1/m] returns nearer than 0.5 m shift too far per step
constexpr double kCoarseStep = 0.01;  // [m] of h in the first pass
constexpr std::size_t kMinBandPoints = 40;  // fewer make a noisy histogram
constexpr double kMinGain = 0.03;           // a band's best h must sharpen it by 3 % to count
constexpr double kMaxBins = 1e6;            // histogram bins: 1 km of spread at 1 mm

// Sum of c log c over the counts c of neighbouring bin pairs of a histogram
// (pairs soften bin-edge effects), i.e. minus their entropy: large when the
// intercepts pile up into peaks.
double sharpness(const std::vector<std::uint32_t>& histogram, std::size_t begin, std::size_t end) {
  static const std::vector<double> table = [] {  // c log c for small c: no log per bin
    std::vector<double> values(4096, 0.0);
    for (std::size_t c = 2; c < values.size(); ++c)
      values[c] = c * std::log(static_cast<double>(c));
    return values;
  }();
  double score = 0.0;
  for (std::size_t b = begin; b + 1 < end; ++b) {
    const std::uint32_t pair = histogram[b] + histogram[b + 1];
    score += pair < table.size() ? table[pair] : pair * std::log(static_cast<double>(pair));
  }
  return score;
}

// Histogram of the intercepts v - h u over [t_low, t_low + size * width).
void bin(const std::vector<Point>& points, double h, double t_low, double width,
         std::vector<std::uint32_t>& histogram) {
  std::fill(histogram.begin(), histogram.end(), 0u);
  const auto size = static_cast<std::ptrdiff_t>(histogram.size());
  const double per_bin = 1.0 / width;
  for (const Point& p : points) {
    const auto b = static_cast<std::ptrdiff_t>((p.v - h * p.u - t_low) * per_bin);
    if (b >= 0 && b < size) ++histogram[b];
  }
}

struct Scan {
  double h = 0.0;     // [m] sharpest offset
  double gain = 0.0;  // its sharpness over that of `center`, minus 1
};

// The sharpest h within center +- range: coarse to fine, each pass searching
// +- one step of the previous around its best with bins as fine as its step
// resolves. Ties keep the value nearest the centre (no evidence, no shift).
Scan scan(const std::vector<Point>& points, double center, double range, double step,
          double bin_width) {
  double t_low = 1e300, t_high = -1e300;
  for (const Point& p : points) {
    t_low = std::min(t_low, p.v - (center + range + step) * p.u);
    t_high = std::max(t_high, p.v - (center - range - step) * p.u);
  }
  std::vector<std::uint32_t> histogram;
  Scan best{center, 0.0};
  double half_range = range;
  for (const double scale : {4.0, 2.0, 1.0}) {  // bin width and step shrink together
    const double width = bin_width * scale, delta = step * scale / 4.0;
    // Returns kilometres away (or garbage) would ask for a histogram without
    // bound: no profile then, rather than an allocation failure.
    const double bins = (t_high - t_low) / width;
    if (!std::isfinite(bins) || bins > kMaxBins) return best;
    histogram.assign(static_cast<std::size_t>(bins) + 2, 0u);
    const auto score_at = [&](double h) {
      bin(points, h, t_low, width, histogram);
      return sharpness(histogram, 0, histogram.size());
    };
    const double middle = best.h;
    const double baseline = score_at(center);
    double best_score = baseline;
    best.h = center;
    const int steps = static_cast<int>(std::lround(half_range / delta));
    for (int k = 0; k <= 2 * steps; ++k) {  // middle, +1, -1, +2, -2, ...
      const double h = middle + (k % 2 ? 1 : -1) * ((k + 1) / 2) * delta;
      if (h == center) continue;
      const double score = score_at(h);
      if (score > best_score * (1.0 + 1e-9)) best_score = score, best.h = h;
    }
    best.gain = baseline > 0.0 ? best_score / baseline - 1.0 : 0.0;
    half_range = delta;
  }
  return best;
}

// A level floor at height -H looks like a laser at elevation 0 with offset -H:
// its returns, from every laser, all lie on z = -H, i.e. on v = -H u, and
// for h near -H the scan squeezes them (a third of a corridor sweep) into a
// few bins, sharper than the real lasers. Returns on a z level that holds
// more than kPlaneShare of them are left out of the scan (a tilted floor does
// not line up, so it does no harm and stays).
void drop_level_planes(std::vector<Point>& points) {
  constexpr double kLevel = 0.02;       // [m] z bins
  constexpr double kPlaneShare = 0.08;  // a laser holds ~1/16 or less, a floor far more
  constexpr long kLevels = 2000;        // z within +-20 m
  const auto level_of = [&](const Point& p) {
    return std::clamp(std::lround(p.v / p.u / kLevel) + kLevels / 2, 0L, kLevels - 1);
  };
  std::vector<std::size_t> count(kLevels, 0);
  for (const Point& p : points) ++count[level_of(p)];
  std::vector<bool> plane(kLevels, false);
  bool any = false;
  for (long level = 1; level + 1 < kLevels; ++level)
    if (count[level] > kPlaneShare * points.size())
      plane[level - 1] = plane[level] = plane[level + 1] = any = true;
  if (!any) return;
  points.erase(std::remove_if(points.begin(), points.end(),
                              [&](const Point& p) { return plane[level_of(p)]; }),
               points.end());
}

}  // namespace

OffsetProfile OffsetProfile::estimate(const std::vector<Point>& all, const ProfileParams& params) {
  std::vector<Point> points;
  const std::size_t stride = std::max<std::size_t>(1, all.size() / params.max_points);
  for (std::size_t i = 0; i < all.size(); i += stride)
    if (all[i].u <= kMaxU) points.push_back(all[i]);
  OffsetProfile profile;
  if (points.size() < kMinBandPoints) return profile;
  drop_level_planes(points);
  if (points.size() < kMinBandPoints) return profile;
  profile.global_ = scan(points, 0.0, params.offset_range, kCoarseStep, params.bin).h;

  // Bands of elevation under the global offset; each gets its own sharpest h.
  const auto intercept = [&](const Point& p) { return p.v - profile.global_ * p.u; };
  std::sort(points.begin(), points.end(),
            [&](const Point& a, const Point& b) { return intercept(a) < intercept(b); });
  std::vector<double> offsets;
  for (std::size_t begin = 0; begin < points.size();) {
    std::size_t end = begin;
    const double start = intercept(points[begin]);
    while (end < points.size() &&
           (intercept(points[end]) - start < params.band_width || end - begin < kMinBandPoints))
      ++end;
    if (points.size() - end < kMinBandPoints) end = points.size();  // no thin last band
    const std::vector<Point> band(points.begin() + begin, points.begin() + end);
    const Scan best = scan(band, profile.global_, params.band_range, 0.006, params.bin);
    if (best.gain > kMinGain) {  // else no evidence either way
      profile.centers_.push_back(0.5 * (start + intercept(points[end - 1])));
      offsets.push_back(best.h);
    }
    begin = end;
  }
  // A band between two lasers sharpens only by chance: such outliers come
  // alone or in twos, so a median of five removes them and keeps a step
  // between blocks of lasers.
  constexpr std::size_t kMedian = 5;
  for (std::size_t b = 0; b < offsets.size(); ++b) {
    const std::size_t first = b >= kMedian / 2 ? b - kMedian / 2 : 0;
    const std::size_t last = std::min(offsets.size(), b + kMedian / 2 + 1);
    std::vector<double> window(offsets.begin() + first, offsets.begin() + last);
    std::nth_element(window.begin(), window.begin() + window.size() / 2, window.end());
    profile.offsets_.push_back(window[window.size() / 2]);
  }
  return profile;
}

double OffsetProfile::at(double t) const {
  if (centers_.empty()) return global_;
  if (t <= centers_.front()) return offsets_.front();
  if (t >= centers_.back()) return offsets_.back();
  const auto upper = std::upper_bound(centers_.begin(), centers_.end(), t) - centers_.begin();
  const double a = centers_[upper - 1], b = centers_[upper];
  const double w = (t - a) / (b - a);
  return (1.0 - w) * offsets_[upper - 1] + w * offsets_[upper];
}

std::pair<double, double> OffsetProfile::sides(double t) const {
  if (centers_.empty()) return {global_, global_};
  if (t <= centers_.front()) return {offsets_.front(), offsets_.front()};
  if (t >= centers_.back()) return {offsets_.back(), offsets_.back()};
  const auto upper = std::upper_bound(centers_.begin(), centers_.end(), t) - centers_.begin();
  return {offsets_[upper - 1], offsets_[upper]};
}

double OffsetProfile::intercept(const Point& p) const {
  double t = p.v - global_ * p.u;
  for (int i = 0; i < 2; ++i) t = p.v - at(t) * p.u;
  return t;
}

}  // namespace l2s::io::fan
