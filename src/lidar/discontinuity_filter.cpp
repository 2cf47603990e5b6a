// Depth discontinuities on the board, paper Sec. III-B (after Levinson & Thrun
// 2013): p_delta = max(r_prev - r, r_next - r, 0) with the azimuthal
// neighbours in the same ring; then the ring filter of Sec. III-C (rings with
// a point count compatible with a circle, outer board points removed).
//
// The file order of a sweep is not trusted: each ring is sorted by azimuth
// here, with the 360-degree wrap. A neighbour farther than gap_factor azimuth
// steps away means returns are missing (sky through a hole, a ray cut by the
// pass-through filter), which counts as infinitely far.
#include <l2s/discontinuity_filter.hpp>

#include <l2s/error.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>

namespace l2s {
namespace {

constexpr double kTwoPi = 2.0 * M_PI;
constexpr double kInf = std::numeric_limits<double>::infinity();

struct RingPoint {
  double azimuth;  // [rad] in (-pi, pi]
  double range;    // [m]
  std::size_t index;
  bool board;
};

/// Azimuth from a to b going counter-clockwise, in [0, 2 pi).
double ccw(double a, double b) {
  const double d = b - a;
  return d < 0.0 ? d + kTwoPi : d;
}

double median_step(const std::vector<RingPoint>& ring) {
  std::vector<double> steps;
  for (std::size_t i = 0; i + 1 < ring.size(); ++i) {
    const double d = ring[i + 1].azimuth - ring[i].azimuth;
    if (d > 1e-9) steps.push_back(d);
  }
  if (steps.empty()) return kTwoPi;
  std::nth_element(steps.begin(), steps.begin() + steps.size() / 2, steps.end());
  return steps[steps.size() / 2];
}

/// The ray at `azimuth` with the elevation of `p`, cut with the plane; `p` when parallel.
Eigen::Vector3d ray_on_plane(const Eigen::Vector3d& p, double azimuth, const Plane& plane) {
  const double elevation = std::atan2(p.z(), std::hypot(p.x(), p.y()));
  const Eigen::Vector3d d(std::cos(elevation) * std::cos(azimuth), std::cos(elevation) * std::sin(azimuth),
                          std::sin(elevation));
  const double denom = plane.normal().dot(d);
  const double t = -plane.offset() / denom;
  return std::abs(denom) > 1e-9 && t > 0.0 ? Eigen::Vector3d(t * d) : p;
}

}  // namespace

void DiscontinuityFilter::Params::validate() const {
  if (!(min_discontinuity > 0.0)) throw ParamError("min_discontinuity", "must be > 0 m");
  if (!(azimuth_step >= 0.0 && azimuth_step < kTwoPi)) throw ParamError("azimuth_step", "must be in [0, 2 pi) rad");
  if (!(gap_factor > 1.0)) throw ParamError("gap_factor", "must be > 1");
  if (min_ring_edges < 1) throw ParamError("min_ring_edges", "must be >= 1");
  if (max_ring_edges < min_ring_edges) throw ParamError("max_ring_edges", "must be >= min_ring_edges");
}

DiscontinuityFilter::Params DiscontinuityFilter::Params::paper() {
  Params params;
  params.placement = EdgePlacement::LastBoardPoint;
  return params;
}

DiscontinuityFilter::DiscontinuityFilter() : DiscontinuityFilter(Params{}) {}

DiscontinuityFilter::DiscontinuityFilter(Params params) : params_(std::move(params)) { params_.validate(); }

DiscontinuityFilter::Result DiscontinuityFilter::filter(const LidarCloud& cloud, const Plane& plane,
                                                        const std::vector<std::size_t>& board_inliers) const {
  Result result;
  if (!cloud.has_ring()) {
    result.reason = "the cloud has no ring field (fill it with l2s::io::recover_rings)";
    return result;
  }
  if (cloud.ring.size() != cloud.size()) throw Error("DiscontinuityFilter: ring and points differ in size");
  std::vector<char> is_board(cloud.size(), 0);
  for (std::size_t i : board_inliers) {
    if (i >= cloud.size()) throw Error("DiscontinuityFilter: board inlier index out of range");
    is_board[i] = 1;
  }

  std::map<std::uint16_t, std::vector<RingPoint>> rings;  // ordered: deterministic output
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const Eigen::Vector3d& p = cloud.points[i];
    if (!p.allFinite()) continue;
    rings[cloud.ring[i]].push_back({std::atan2(p.y(), p.x()), p.norm(), i, is_board[i] != 0});
  }

  for (auto& [ring_id, ring] : rings) {
    if (std::none_of(ring.begin(), ring.end(), [](const RingPoint& q) { return q.board; })) continue;
    ++result.counts.rings;
    // Sort by azimuth; ties by range so that any input order gives one answer.
    std::sort(ring.begin(), ring.end(), [](const RingPoint& a, const RingPoint& b) {
      return a.azimuth != b.azimuth ? a.azimuth < b.azimuth : a.range < b.range;
    });
    const std::size_t m = ring.size();
    const double step = params_.azimuth_step > 0.0 ? params_.azimuth_step : median_step(ring);
    const double max_gap = params_.gap_factor * step;

    // The board segment: board points after the widest azimuth gap between them.
    std::vector<std::size_t> board;
    for (std::size_t i = 0; i < m; ++i)
      if (ring[i].board) board.push_back(i);
    result.counts.board_points += board.size();
    std::size_t first = 0;
    double widest = -1.0;
    for (std::size_t k = 0; k < board.size(); ++k) {
      const std::size_t prev = board[(k + board.size() - 1) % board.size()];
      const double gap = board.size() == 1 ? kTwoPi : ccw(ring[prev].azimuth, ring[board[k]].azimuth);
      if (gap > widest) widest = gap, first = k;
    }
    const std::size_t segment_first = board[first];
    const std::size_t segment_last = board[(first + board.size() - 1) % board.size()];

    struct Edge { std::size_t i; int side; };  // side: -1 jump to the previous point, +1 to the next
    std::vector<Edge> edges;
    for (std::size_t i : board) {
      const std::size_t prev = (i + m - 1) % m, next = (i + 1) % m;
      const double gap_prev = m == 1 ? kTwoPi : ccw(ring[prev].azimuth, ring[i].azimuth);
      const double gap_next = m == 1 ? kTwoPi : ccw(ring[i].azimuth, ring[next].azimuth);
      const double r_prev = gap_prev <= max_gap ? ring[prev].range : kInf;
      const double r_next = gap_next <= max_gap ? ring[next].range : kInf;
      const double jump_prev = r_prev - ring[i].range, jump_next = r_next - ring[i].range;
      if (std::max({jump_prev, jump_next, 0.0}) < params_.min_discontinuity) continue;
      ++result.counts.discontinuities;
      if (params_.drop_border_points && (i == segment_first || i == segment_last)) {
        ++result.counts.border_points;
        continue;
      }
      edges.push_back({i, jump_next >= jump_prev ? +1 : -1});
    }
    if (edges.empty()) continue;
    const int count = static_cast<int>(edges.size());
    if (count < params_.min_ring_edges || count > params_.max_ring_edges) {
      ++result.counts.rings_rejected;
      continue;
    }
    ++result.counts.rings_kept;

    for (const Edge& edge : edges) {
      const RingPoint& q = ring[edge.i];
      const Eigen::Vector3d& p = cloud.points[q.index];
      Eigen::Vector3d placed = p;
      if (params_.placement == EdgePlacement::Midpoint) {
        // The true edge lies between this ray and the next return's; a missing
        // return is taken one azimuth step away.
        const std::size_t j = (edge.i + m + edge.side) % m;
        const double gap = edge.side > 0 ? ccw(q.azimuth, ring[j].azimuth) : ccw(ring[j].azimuth, q.azimuth);
        const double half = 0.5 * (gap <= max_gap && m > 1 ? gap : step);
        placed = ray_on_plane(p, q.azimuth + edge.side * half, plane);
      }
      result.edges.push_back(placed);
      result.rings.push_back(ring_id);
      result.sources.push_back(q.index);
    }
  }

  result.found = !result.edges.empty();
  if (!result.found) {
    std::ostringstream reason;
    reason << "no hole edges: " << result.counts.rings << " ring(s) on the board, " << result.counts.board_points
           << " board points, " << result.counts.discontinuities << " discontinuities, "
           << result.counts.border_points << " on the border, " << result.counts.rings_rejected
           << " ring(s) with an edge count outside [" << params_.min_ring_edges << ", " << params_.max_ring_edges
           << "]";
    result.reason = reason.str();
  }
  return result;
}

}  // namespace l2s
