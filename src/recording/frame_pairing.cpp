// Pairing in time: sweeps take their nearest left image within the
// tolerance (nearest sweep first, so that a contested image goes to the
// sweep it is nearer), left images their nearest right one within the
// stereo tolerance. What is left out is said, stamp by stamp.
#include <l2s/recording/frame_pairing.hpp>

#include <l2s/error.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>

namespace l2s {
namespace {

std::string seconds(std::int64_t ns) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3f s", static_cast<double>(ns) * 1e-9);
  return text;
}

std::string milliseconds(double s) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f ms", s * 1e3);
  return text;
}

/// The index of the stamp in `sorted` (indices into `stamps`, by stamp) nearest `t`.
std::size_t nearest(const std::vector<std::int64_t>& stamps, const std::vector<std::size_t>& sorted, std::int64_t t) {
  const auto after = std::lower_bound(sorted.begin(), sorted.end(), t,
                                      [&](std::size_t i, std::int64_t value) { return stamps[i] < value; });
  if (after == sorted.end()) return sorted.back();
  if (after == sorted.begin()) return *after;
  const std::size_t before = *(after - 1);
  return t - stamps[before] <= stamps[*after] - t ? before : *after;
}

std::vector<std::size_t> by_stamp(const std::vector<std::int64_t>& stamps) {
  std::vector<std::size_t> order(stamps.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return stamps[a] < stamps[b]; });
  return order;
}

double median_period_s(const std::vector<std::int64_t>& stamps, const std::vector<std::size_t>& sorted) {
  std::vector<double> periods;
  for (std::size_t k = 1; k < sorted.size(); ++k)
    if (stamps[sorted[k]] > stamps[sorted[k - 1]]) periods.push_back((stamps[sorted[k]] - stamps[sorted[k - 1]]) * 1e-9);
  if (periods.empty()) return 0.0;
  std::nth_element(periods.begin(), periods.begin() + static_cast<std::ptrdiff_t>(periods.size() / 2), periods.end());
  return periods[periods.size() / 2];
}

}  // namespace

FramePairing pair_in_time(const std::vector<std::int64_t>& lidar, const std::vector<std::int64_t>& left,
                          const std::vector<std::int64_t>& right, const PairingParams& params) {
  if (params.tolerance_s < 0.0) throw ParamError("tolerance_s", "must be >= 0 s");
  if (!(params.stereo_tolerance_s >= 0.0)) throw ParamError("stereo_tolerance_s", "must be >= 0 s");
  FramePairing out;
  const auto lidar_order = by_stamp(lidar), left_order = by_stamp(left), right_order = by_stamp(right);
  const double period = median_period_s(lidar, lidar_order);
  // One sweep alone has no period: any tolerance would be a guess; 50 ms is half a 10 Hz sweep.
  out.tolerance_s = params.tolerance_s > 0.0 ? params.tolerance_s : period > 0.0 ? 0.5 * period : 0.05;
  const auto tolerance_ns = static_cast<std::int64_t>(std::llround(out.tolerance_s * 1e9));
  const auto stereo_ns = static_cast<std::int64_t>(std::llround(params.stereo_tolerance_s * 1e9));

  // Each sweep's nearest left image; contested images go to the nearest sweep.
  constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();
  std::vector<std::size_t> left_of(lidar.size(), kNone), taken_by(left.size(), kNone);
  for (std::size_t s = 0; s < lidar.size(); ++s) {
    if (left.empty()) {
      out.dropped.push_back("sweep at " + seconds(lidar[s]) + ": no " + params.left_name + " in the recording");
      continue;
    }
    const std::size_t image = nearest(left, left_order, lidar[s]);
    const std::int64_t gap = std::llabs(left[image] - lidar[s]);
    if (gap > tolerance_ns) {
      out.dropped.push_back("sweep at " + seconds(lidar[s]) + ": the nearest " + params.left_name + " is " +
                            milliseconds(gap * 1e-9) + " away (tolerance " + milliseconds(out.tolerance_s) + ")");
      continue;
    }
    const std::size_t rival = taken_by[image];
    if (rival != kNone && std::llabs(left[image] - lidar[rival]) <= gap) {
      out.dropped.push_back("sweep at " + seconds(lidar[s]) + ": its nearest " + params.left_name + " went to the nearer sweep at " +
                            seconds(lidar[rival]));
      continue;
    }
    if (rival != kNone) {
      left_of[rival] = kNone;
      out.dropped.push_back("sweep at " + seconds(lidar[rival]) + ": its nearest " + params.left_name + " went to the nearer sweep at " +
                            seconds(lidar[s]));
    }
    taken_by[image] = s;
    left_of[s] = image;
  }

  std::vector<bool> right_used(right.size(), false);
  for (const std::size_t s : lidar_order) {
    if (left_of[s] == kNone) continue;
    PairedFrame frame{s, left_of[s], 0};
    if (!right.empty()) {
      const std::size_t r = nearest(right, right_order, left[frame.left]);
      const std::int64_t gap = std::llabs(right[r] - left[frame.left]);
      if (gap > stereo_ns || right_used[r]) {
        out.dropped.push_back("sweep at " + seconds(lidar[s]) + ": its " + params.left_name + " at " + seconds(left[frame.left]) +
                              (gap > stereo_ns ? " has no " + params.right_name + " within " +
                                                     milliseconds(params.stereo_tolerance_s) + " (nearest " +
                                                     milliseconds(gap * 1e-9) + ")"
                                               : " has no " + params.right_name + " of its own"));
        taken_by[frame.left] = kNone;
        continue;
      }
      right_used[r] = true;
      frame.right = r;
    }
    out.frames.push_back(frame);
  }
  std::size_t unused_left = 0, unused_right = 0;
  for (std::size_t i = 0; i < left.size(); ++i) unused_left += taken_by[i] == kNone;
  for (std::size_t i = 0; i < right.size(); ++i) unused_right += !right_used[i];
  if (unused_left > 0 && !lidar.empty())
    out.dropped.push_back(std::to_string(unused_left) + " " + params.left_name + "(s) in no frame");
  if (unused_right > 0 && !lidar.empty())
    out.dropped.push_back(std::to_string(unused_right) + " " + params.right_name + "(s) in no frame");
  return out;
}

}  // namespace l2s
