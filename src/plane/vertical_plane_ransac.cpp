// RANSAC for the board plane (paper Sec. III-B): a tight distance threshold
// delta_plane and a plane required to be parallel to the sensor's vertical
// axis within alpha_plane.
//
// Written with Eigen instead of PCL's SACSegmentation (SACMODEL_PARALLEL_PLANE):
// PCL seeds its own generator (no seed parameter, so no control over
// determinism), always scores every hypothesis on the whole cloud, and samples
// three points uniformly. The board is a few percent of a lidar sweep, so a
// uniform triple lands on it with probability ~w^3; here the second and third
// points come from the first one's neighbourhood (a grid of sample_radius
// cells), which makes that ~w. Hypotheses are scored on a random prefix first
// and only promising ones on all samples, so a million-point stereo cloud costs
// about as much as a lidar sweep. This file includes no PCL header.
#include "plane/vertical_plane_ransac.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <unordered_map>

namespace l2s::detail {
namespace {

constexpr std::size_t kPrefix = 2000;      // samples used to pre-score a hypothesis
constexpr double kPrefixKeep = 0.7;        // full scoring only within this factor of the best
constexpr double kLocalAllInlier = 0.25;   // assumed P(2nd and 3rd point on the plane | 1st is)
constexpr int kMinIterations = 100;
constexpr double kMinSinTriangle = 0.1;    // rejects nearly collinear triples (one lidar ring)

std::uint64_t cell_key(const Eigen::Vector3i& c) {
  const auto pack = [](int v) { return static_cast<std::uint64_t>(static_cast<std::uint32_t>(v) & 0x1FFFFFu); };
  return (pack(c.x()) << 42) | (pack(c.y()) << 21) | pack(c.z());
}

/// The samples hashed into cubes of sample_radius, so that the second and
/// third point of a triple come from the first one's neighbourhood.
class NeighbourGrid {
 public:
  NeighbourGrid(const std::vector<Eigen::Vector3d>& samples, double cell_size)
      : samples_(samples), inv_cell_(1.0 / cell_size) {
    grid_.reserve(samples.size() / 4 + 1);
    for (std::size_t i = 0; i < samples.size(); ++i)
      grid_[cell_key(cell_of(samples[i]))].push_back(static_cast<int>(i));
  }

  /// Draws b and c uniformly from the samples in the 27 cells around
  /// samples[a]; false when fewer than three are there.
  bool draw_two(std::size_t a, std::mt19937_64& rng, std::size_t& b, std::size_t& c) const {
    const Eigen::Vector3i ca = cell_of(samples_[a]);
    std::array<const std::vector<int>*, 27> lists{};
    std::size_t lists_count = 0, total = 0;
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const auto it = grid_.find(cell_key(ca + Eigen::Vector3i(dx, dy, dz)));
          if (it == grid_.end()) continue;
          lists[lists_count++] = &it->second;
          total += it->second.size();
        }
    if (total < 3) return false;
    std::uniform_int_distribution<std::size_t> pick_near(0, total - 1);
    const auto nth_neighbour = [&](std::size_t k) {
      for (std::size_t l = 0; l < lists_count; ++l) {
        if (k < lists[l]->size()) return static_cast<std::size_t>((*lists[l])[k]);
        k -= lists[l]->size();
      }
      return a;
    };
    b = nth_neighbour(pick_near(rng));
    c = nth_neighbour(pick_near(rng));
    return true;
  }

 private:
  Eigen::Vector3i cell_of(const Eigen::Vector3d& p) const {
    return Eigen::Vector3i((p * inv_cell_).array().floor().cast<int>());
  }

  const std::vector<Eigen::Vector3d>& samples_;
  double inv_cell_;  // [1/m]
  std::unordered_map<std::uint64_t, std::vector<int>> grid_;
};

/// The plane through samples a, b, c, unless they are nearly collinear or its
/// normal breaks the axis constraints (max_sin_axis, min_cos_axis).
std::optional<Plane> plane_through(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                                   const VerticalPlaneRansacParams& params) {
  const Eigen::Vector3d ab = b - a;
  const Eigen::Vector3d ac = c - a;
  Eigen::Vector3d normal = ab.cross(ac);
  const double area = normal.norm();
  if (!(area > kMinSinTriangle * ab.norm() * ac.norm())) return std::nullopt;
  normal /= area;
  const double along_axis = std::abs(normal.dot(params.axis));
  if (along_axis > params.max_sin_axis || along_axis < params.min_cos_axis) return std::nullopt;
  return Plane(normal, a);
}

/// Samples [0, end) within the consensus distance of the plane.
std::size_t consensus(const std::vector<Eigen::Vector3d>& samples, const VerticalPlaneRansacParams& params,
                      const Plane& plane, std::size_t end) {
  std::size_t inliers = 0;
  for (std::size_t i = 0; i < end; ++i)
    if (std::abs(plane.signedDistance(samples[i])) <=
        (params.tolerance ? (*params.tolerance)[i] : params.distance_threshold))
      ++inliers;
  return inliers;
}

/// Adaptive stop: enough draws to hit a plane with this support with 99%
/// odds, within [kMinIterations, max_iterations]; `current` when the odds
/// are degenerate.
int needed_iterations(int current, std::size_t support, std::size_t n, int max_iterations) {
  const double p_good = kLocalAllInlier * static_cast<double>(support) / static_cast<double>(n);
  if (!(p_good > 0.0 && p_good < 1.0)) return current;
  const double draws = std::log(0.01) / std::log(1.0 - p_good);
  return std::min(max_iterations, std::max(kMinIterations, static_cast<int>(std::ceil(draws))));
}

}  // namespace

VerticalPlaneRansacResult find_vertical_plane(const std::vector<Eigen::Vector3d>& samples,
                                              const VerticalPlaneRansacParams& params,
                                              std::mt19937_64& rng) {
  VerticalPlaneRansacResult result;
  const std::size_t n = samples.size();
  if (n < 3) return result;
  const NeighbourGrid grid(samples, params.sample_radius);
  const std::size_t prefix = std::min(n, kPrefix);
  std::uniform_int_distribution<std::size_t> pick_first(0, n - 1);
  std::size_t best_prefix = 0;
  int needed = params.max_iterations;
  for (int iteration = 0; iteration < needed; ++iteration) {
    const std::size_t a = pick_first(rng);
    std::size_t b = 0, c = 0;
    if (!grid.draw_two(a, rng, b, c)) continue;
    if (b == a || c == a || b == c) continue;
    const std::optional<Plane> hypothesis = plane_through(samples[a], samples[b], samples[c], params);
    if (!hypothesis) continue;
    // Pre-score on the prefix; only promising hypotheses are scored on all samples.
    const std::size_t pre = consensus(samples, params, *hypothesis, prefix);
    if (static_cast<double>(pre) < kPrefixKeep * static_cast<double>(best_prefix)) continue;
    const std::size_t full = prefix == n ? pre : consensus(samples, params, *hypothesis, n);
    if (full <= result.consensus) continue;

    result.found = true;
    result.plane = *hypothesis;
    result.consensus = full;
    best_prefix = pre;
    needed = needed_iterations(needed, full, n, params.max_iterations);
  }
  return result;
}

}  // namespace l2s::detail
