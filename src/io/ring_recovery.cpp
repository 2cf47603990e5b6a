// Ring recovery from elevation angles: sort the elevations, split them where
// consecutive values are further apart than min_gap, fold stray points into the
// nearest ring, then number the rings from the lowest. Beams without returns
// are recognised where the spacing is regular: a gap of ~k local spacings
// between two rings skips k - 1 indices. The local spacing is the median of up
// to four gaps on each side; it is trusted only when no gap there is much
// smaller than it (uniform sensors, and HDL-64E's two blocks), so sensors with
// a deliberately uneven fan (VLP-32C) are numbered consecutively instead.
#include <l2s/io/ring_recovery.hpp>

#include <l2s/error.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

namespace l2s::io {
namespace {

constexpr int kWindow = 4;               // gaps looked at on each side
constexpr double kRegularSpacing = 0.6;  // smallest gap / median at least this = regular
constexpr double kMinRange = 1e-6;       // [m] points closer than this are "no return"

struct Cluster {
  std::size_t begin, end;  // range in the sorted elevations
  std::size_t size() const { return end - begin; }
};

std::vector<Cluster> split(const std::vector<std::pair<double, std::size_t>>& sorted,
                           double min_gap) {
  std::vector<Cluster> clusters;
  for (std::size_t i = 0; i < sorted.size(); ++i)
    if (i == 0 || sorted[i].first - sorted[i - 1].first > min_gap)
      clusters.push_back({i, i + 1});
    else
      clusters.back().end = i + 1;
  return clusters;
}

// One sweep from the lowest: a small cluster joins the neighbour it is closer to.
std::vector<Cluster> merge_small(const std::vector<Cluster>& clusters,
                                 const std::vector<std::pair<double, std::size_t>>& sorted,
                                 std::size_t min_points) {
  std::vector<Cluster> merged;
  for (std::size_t k = 0; k < clusters.size(); ++k) {
    Cluster c = clusters[k];
    if (!merged.empty() && merged.back().size() < min_points) {  // the last one was small
      merged.back().end = c.end;
      continue;
    }
    if (c.size() < min_points && !merged.empty()) {
      const double gap_below = sorted[c.begin].first - sorted[merged.back().end - 1].first;
      const bool has_above = k + 1 < clusters.size();
      const double gap_above = has_above
                                   ? sorted[clusters[k + 1].begin].first - sorted[c.end - 1].first
                                   : std::numeric_limits<double>::infinity();
      if (gap_below <= gap_above) {
        merged.back().end = c.end;
        continue;
      }
    }
    merged.push_back(c);  // a small one here is joined by the next cluster
  }
  return merged;
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

// Index of each cluster, skipping indices of beams that returned nothing.
std::vector<int> number(const std::vector<double>& centers, bool infer_missing) {
  std::vector<int> index(centers.size(), 0);
  std::vector<double> gaps;
  for (std::size_t k = 1; k < centers.size(); ++k) gaps.push_back(centers[k] - centers[k - 1]);
  for (std::size_t j = 0; j < gaps.size(); ++j) {
    int steps = 1;
    std::vector<double> window;
    for (std::size_t w = j >= kWindow ? j - kWindow : 0; w <= j + kWindow && w < gaps.size(); ++w)
      if (w != j) window.push_back(gaps[w]);
    if (infer_missing && window.size() >= 2) {
      const double spacing = median(window);
      const double smallest = *std::min_element(window.begin(), window.end());
      if (spacing > 0.0 && smallest >= kRegularSpacing * spacing)
        steps = std::max(1, static_cast<int>(std::lround(gaps[j] / spacing)));
    }
    index[j + 1] = std::min(index[j] + steps, int{std::numeric_limits<std::uint16_t>::max()});
  }
  return index;
}

}  // namespace

void RingRecoveryParams::validate() const {
  if (!(min_gap > 0.0) || !std::isfinite(min_gap))
    throw ParamError("min_gap", "must be a positive angle in radians");
  if (min_points_per_ring < 1) throw ParamError("min_points_per_ring", "must be at least 1");
}

int recover_rings(LidarCloud& cloud, const RingRecoveryParams& params) {
  params.validate();
  std::vector<std::pair<double, std::size_t>> sorted;  // (elevation, point index)
  sorted.reserve(cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const Eigen::Vector3d& p = cloud.points[i];
    if (!p.allFinite() || p.norm() < kMinRange) continue;
    sorted.emplace_back(std::atan2(p.z(), std::hypot(p.x(), p.y())), i);
  }
  std::sort(sorted.begin(), sorted.end());
  cloud.ring.assign(cloud.size(), 0);
  if (sorted.empty()) return 0;

  const auto clusters = merge_small(split(sorted, params.min_gap), sorted,
                                    static_cast<std::size_t>(params.min_points_per_ring));
  std::vector<double> centers;  // medians: robust to the stray points folded in
  for (const Cluster& c : clusters) centers.push_back(sorted[c.begin + c.size() / 2].first);
  const std::vector<int> index = number(centers, params.infer_missing_beams);
  for (std::size_t k = 0; k < clusters.size(); ++k)
    for (std::size_t s = clusters[k].begin; s < clusters[k].end; ++s)
      cloud.ring[sorted[s].second] = static_cast<std::uint16_t>(index[k]);
  return index.back() + 1;
}

}  // namespace l2s::io
