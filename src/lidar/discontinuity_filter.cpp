// Depth discontinuities on the board, paper Sec. III-B (after Levinson & Thrun
// 2013), and the ring filter of Sec. III-C, made robust to real sweeps.
//
// The paper marks a board point whose azimuthal neighbour is >= delta_discont
// farther away, keeps rings whose count of such points fits a circle and drops
// each ring's outer points. Real sweeps break the count: a stray return inside
// a hole (the beam footprint still on the rim, a hit on the hole's inner wall)
// or a mixed return at a border adds edges, and the ring is lost. Here each
// ring (sorted by azimuth, file order is not trusted) is cut into runs of
// board points and the gaps between them, and each gap is classified by what
// the rays in it saw:
//   - see-through: returns at least delta_discont behind the board plane along
//     their ray, or no return at all (sky, out of range): the board is open;
//   - occlusion: a return in front of the plane hides the board;
//   - unclear: only returns near the plane that are not board inliers.
// A run between see-through gaps that is too short to be board material (at
// most max_stray_points returns, or narrower than half the narrowest strip of
// the board: between two holes, or between a hole and the border) is a stray
// and joins them; a ring grazing a hole sees many such mixed returns. The ring's first and last runs end at the board's
// outer border (never edges); a see-through gap between two runs is a hole
// crossing when it is no wider than a hole, and gives two edges.
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

/// What one return says about the board at its azimuth.
enum class Kind { Board, Behind, Front, Near };

struct RingPoint {
  double azimuth;  // [rad] in (-pi, pi]
  double range;    // [m]
  std::size_t index;
  Kind kind;
  Eigen::Vector3d point;
};

/// A gap between two runs of board points, classified by the returns in it.
enum class GapKind { SeeThrough, Occlusion, Unclear };

struct Run {
  std::size_t first, last;  // positions in the azimuth-sorted ring (circular)
  int points;               // board points in the run
};

/// [m] The narrowest strip of board material a ring can cross: between two
/// holes of a row, or between a hole and the border.
double narrowest_strip(const Target& target) {
  const double between = target.hole_spacing_x - 2.0 * target.hole_radius;
  const double to_border = 0.5 * (target.board_width - target.hole_spacing_x) - target.hole_radius;
  return std::max(0.0, std::min(between, to_border));
}

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

/// Where a non-board return lies relative to the board plane along its own ray.
Kind classify(const Eigen::Vector3d& p, const Plane& plane, double min_discontinuity) {
  const double range = p.norm();
  const double denom = plane.normal().dot(p / range);
  const double t = std::abs(denom) > 1e-9 ? -plane.offset() / denom : -1.0;
  if (t <= 0.0) return Kind::Near;  // the ray never meets the plane: says nothing about it
  if (range >= t + min_discontinuity) return Kind::Behind;
  if (range <= t - min_discontinuity) return Kind::Front;
  return Kind::Near;
}

/// One ring's hole edges: positions in `ring` and the side of the jump
/// (+1: the hole follows, -1: it precedes).
struct RingEdges {
  std::vector<std::pair<std::size_t, int>> edges;
  DiscontinuityFilter::Counts counts;
};

class RingClassifier {
 public:
  RingClassifier(const std::vector<RingPoint>& ring, double step, const DiscontinuityFilter::Params& params,
                 const Target& target)
      : ring_(ring), step_(step), max_gap_(params.gap_factor * step), params_(params), target_(target) {}

  RingEdges classify() {
    RingEdges out;
    const std::vector<Run> runs = without_strays(board_runs(), out.counts);
    if (runs.empty()) return out;
    out.counts.border_points += runs.size() == 1 && runs[0].first == runs[0].last ? 1 : 2;
    for (std::size_t k = 0; k + 1 < runs.size(); ++k) {
      const GapKind kind = gap_kind(runs[k].last, runs[k + 1].first);
      if (kind == GapKind::Occlusion) ++out.counts.occlusions;
      if (kind != GapKind::SeeThrough) continue;
      if (!hole_sized(runs[k].last, runs[k + 1].first)) {
        ++out.counts.wide_gaps;
        continue;
      }
      ++out.counts.hole_crossings;
      out.edges.emplace_back(runs[k].last, +1);
      out.edges.emplace_back(runs[k + 1].first, -1);
    }
    return out;
  }

 private:
  std::size_t next(std::size_t i) const { return (i + 1) % ring_.size(); }
  double gap_after(std::size_t i) const {
    return ring_.size() == 1 ? kTwoPi : ccw(ring_[i].azimuth, ring_[next(i)].azimuth);
  }

  /// Maximal runs of consecutive board points over the ring's board segment:
  /// from the board point after the widest gap between board points, round.
  std::vector<Run> board_runs() const {
    std::vector<std::size_t> board;
    for (std::size_t i = 0; i < ring_.size(); ++i)
      if (ring_[i].kind == Kind::Board) board.push_back(i);
    std::size_t start = 0;
    double widest = -1.0;
    for (std::size_t k = 0; k < board.size(); ++k) {
      const std::size_t prev = board[(k + board.size() - 1) % board.size()];
      const double gap = board.size() == 1 ? kTwoPi : ccw(ring_[prev].azimuth, ring_[board[k]].azimuth);
      if (gap > widest) widest = gap, start = k;
    }
    std::vector<Run> runs;
    const std::size_t last_board = board[(start + board.size() - 1) % board.size()];
    for (std::size_t i = board[start];; i = next(i)) {
      if (ring_[i].kind == Kind::Board) {
        const bool joins = !runs.empty() && runs.back().last == (i + ring_.size() - 1) % ring_.size() &&
                           gap_after(runs.back().last) <= max_gap_;
        if (joins)
          runs.back().last = i, ++runs.back().points;
        else
          runs.push_back({i, i, 1});
      }
      if (i == last_board) break;
    }
    return runs;
  }

  /// Short runs with see-through on both sides are stray returns inside a hole
  /// (or just beyond the border); they are dropped and their gaps fuse.
  std::vector<Run> without_strays(std::vector<Run> runs, DiscontinuityFilter::Counts& counts) const {
    std::vector<Run> kept;
    for (std::size_t k = 0; k < runs.size(); ++k) {
      const Run& run = runs[k];
      const bool open_before = k == 0 ? outer_side_open(run.first, -1)
                                      : gap_kind(runs[k - 1].last, run.first) == GapKind::SeeThrough;
      const bool open_after = k + 1 == runs.size() ? outer_side_open(run.last, +1)
                                                   : gap_kind(run.last, runs[k + 1].first) == GapKind::SeeThrough;
      const double span = (ring_[run.first].point - ring_[run.last].point).norm();
      const bool short_run = run.points <= params_.max_stray_points || span < 0.5 * narrowest_strip(target_);
      if (short_run && open_before && open_after && runs.size() > 1) {
        counts.stray_points += static_cast<std::size_t>(run.points);
        continue;
      }
      kept.push_back(run);
    }
    return kept;
  }

  /// Does the ring see through beyond the board's outer end at position i?
  bool outer_side_open(std::size_t i, int side) const {
    const std::size_t j = side > 0 ? next(i) : (i + ring_.size() - 1) % ring_.size();
    const double gap = side > 0 ? gap_after(i) : gap_after(j);
    return gap > max_gap_ || ring_[j].kind == Kind::Behind;
  }

  /// What the returns strictly between positions a and b (circular) saw.
  GapKind gap_kind(std::size_t a, std::size_t b) const {
    bool through = false;
    for (std::size_t i = a; i != b; i = next(i)) {
      if (gap_after(i) > max_gap_) through = true;  // missing returns
      const std::size_t j = next(i);
      if (j == b) break;
      if (ring_[j].kind == Kind::Front) return GapKind::Occlusion;
      if (ring_[j].kind == Kind::Behind) through = true;
    }
    return through ? GapKind::SeeThrough : GapKind::Unclear;
  }

  /// Is the gap between the board returns at a and b no wider than a hole?
  bool hole_sized(std::size_t a, std::size_t b) const {
    // Both ends are board returns, so their distance is the gap's width in the
    // plane, whatever the board's yaw.
    const double step_width = step_ * std::max(ring_[a].range, ring_[b].range);
    const double width = (ring_[a].point - ring_[b].point).norm();
    return width <= 2.0 * target_.hole_radius * (1.0 + params_.hole_gap_tolerance) + 2.0 * step_width;
  }

 private:
  const std::vector<RingPoint>& ring_;
  double step_;     // [rad] azimuth step of the ring
  double max_gap_;  // [rad] wider azimuth gaps mean missing returns
  const DiscontinuityFilter::Params& params_;
  const Target& target_;
};

void add_counts(DiscontinuityFilter::Counts& total, const DiscontinuityFilter::Counts& ring) {
  total.stray_points += ring.stray_points;
  total.hole_crossings += ring.hole_crossings;
  total.wide_gaps += ring.wide_gaps;
  total.occlusions += ring.occlusions;
  total.border_points += ring.border_points;
}

std::string no_edges_reason(const DiscontinuityFilter::Counts& c, int max_ring_edges) {
  std::ostringstream reason;
  reason << "no hole edges: " << c.rings << " ring(s) on the board, " << c.board_points << " board points, "
         << c.hole_crossings << " hole crossings, " << c.wide_gaps << " see-through gaps wider than a hole, "
         << c.occlusions << " occlusions, " << c.stray_points << " stray returns, " << c.rings_rejected
         << " ring(s) with more than " << max_ring_edges << " hole edges";
  return reason.str();
}

}  // namespace

void DiscontinuityFilter::Params::validate() const {
  if (!(min_discontinuity > 0.0)) throw ParamError("min_discontinuity", "must be > 0 m");
  if (!(azimuth_step >= 0.0 && azimuth_step < kTwoPi)) throw ParamError("azimuth_step", "must be in [0, 2 pi) rad");
  if (!(gap_factor > 1.0)) throw ParamError("gap_factor", "must be > 1");
  if (max_stray_points < 0) throw ParamError("max_stray_points", "must be >= 0");
  if (!(hole_gap_tolerance >= 0.0)) throw ParamError("hole_gap_tolerance", "must be >= 0");
  if (max_ring_edges < 2) throw ParamError("max_ring_edges", "must be >= 2");
}

DiscontinuityFilter::Params DiscontinuityFilter::Params::paper() {
  Params params;
  params.min_discontinuity = 0.5;
  params.placement = EdgePlacement::LastBoardPoint;
  return params;
}

DiscontinuityFilter::DiscontinuityFilter() : DiscontinuityFilter(Params{}) {}

DiscontinuityFilter::DiscontinuityFilter(Params params) : params_(std::move(params)) { params_.validate(); }

DiscontinuityFilter::Result DiscontinuityFilter::filter(const LidarCloud& cloud, const Plane& plane,
                                                        const std::vector<std::size_t>& board_inliers,
                                                        const Target& target) const {
  Result result;
  if (!cloud.has_ring()) {
    result.reason = "the cloud has no ring field (fill it with l2s::io::recover_rings)";
    return result;
  }
  if (cloud.ring.size() != cloud.size()) throw ParamError("cloud.ring", "must have one value per point");
  if (!plane.coeffs().allFinite()) {
    result.reason = "the plane is not finite";
    return result;
  }
  std::vector<char> is_board(cloud.size(), 0);
  for (std::size_t i : board_inliers) {
    if (i >= cloud.size()) throw ParamError("board_inliers", "index past the end of the cloud");
    is_board[i] = 1;
  }

  std::map<std::uint16_t, std::vector<RingPoint>> rings;  // ordered: deterministic output
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const Eigen::Vector3d& p = cloud.points[i];
    if (!p.allFinite() || p.norm() < 1e-9) continue;
    const Kind kind = is_board[i] ? Kind::Board : classify(p, plane, params_.min_discontinuity);
    rings[cloud.ring[i]].push_back({std::atan2(p.y(), p.x()), p.norm(), i, kind, p});
  }

  for (auto& [ring_id, ring] : rings) {
    const auto board_count = std::count_if(ring.begin(), ring.end(), [](const RingPoint& q) { return q.kind == Kind::Board; });
    if (board_count == 0) continue;
    ++result.counts.rings;
    result.counts.board_points += static_cast<std::size_t>(board_count);
    // Sort by azimuth; ties by range so that any input order gives one answer.
    std::sort(ring.begin(), ring.end(), [](const RingPoint& a, const RingPoint& b) {
      return a.azimuth != b.azimuth ? a.azimuth < b.azimuth : a.range < b.range;
    });
    const std::size_t m = ring.size();
    const double step = params_.azimuth_step > 0.0 ? params_.azimuth_step : median_step(ring);
    const double max_gap = params_.gap_factor * step;
    const RingEdges found = RingClassifier(ring, step, params_, target).classify();
    add_counts(result.counts, found.counts);
    if (found.edges.empty()) continue;
    if (static_cast<int>(found.edges.size()) > params_.max_ring_edges) {
      ++result.counts.rings_rejected;
      continue;
    }
    ++result.counts.rings_kept;

    for (const auto& [position, side] : found.edges) {
      const RingPoint& q = ring[position];
      const Eigen::Vector3d& p = cloud.points[q.index];
      // The true edge lies between this ray and the next return's; a missing
      // return is taken one azimuth step away.
      const std::size_t j = (position + m + side) % m;
      const double gap = side > 0 ? ccw(q.azimuth, ring[j].azimuth) : ccw(ring[j].azimuth, q.azimuth);
      const double half = 0.5 * (gap <= max_gap && m > 1 ? gap : step);
      const Eigen::Vector3d placed =
          params_.placement == EdgePlacement::Midpoint ? ray_on_plane(p, q.azimuth + side * half, plane) : p;
      result.crossings.push_back(
          {ray_on_plane(p, q.azimuth, plane), ray_on_plane(p, q.azimuth + 2.0 * side * half, plane)});
      result.edges.push_back(placed);
      result.rings.push_back(ring_id);
      result.sources.push_back(q.index);
    }
  }

  result.found = !result.edges.empty();
  if (!result.found) result.reason = no_edges_reason(result.counts, params_.max_ring_edges);
  return result;
}

}  // namespace l2s
