#pragma once
// Lidar depth discontinuities on the board (paper Sec. III-B, after Levinson
// and Thrun 2013) and the ring filter of Sec. III-C: the points where a ring
// leaves the board through a hole, as edge points for the circle finder.
//
// Real sweeps carry stray board-plane returns inside a hole, mixed returns at
// rims and borders, and rings that only graze a hole, so edges are not
// counted per ring: each ring is cut into runs of board points and the gaps
// between them, and every gap is classified (a hole crossed, a stray return
// inside a hole, an occluder in front, or the board's outer border).

#include <l2s/export.hpp>
#include <l2s/geometry.hpp>
#include <l2s/target.hpp>
#include <l2s/types.hpp>

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace l2s {

/// Finds the hole edges of the board along each lidar ring.
/// Thread safety: holds only what it was built with; its const functions may
/// run concurrently on one instance, and each call is deterministic (random
/// draws are seeded per call from the params).
class L2S_EXPORT DiscontinuityFilter {
 public:
  /// Where an edge point is placed.
  enum class EdgePlacement {
    LastBoardPoint,  ///< the last board return before the jump (paper)
    Midpoint,        ///< the board plane hit by the ray halfway (in azimuth) to the next return
  };

  struct Params {
    double min_discontinuity = 0.15;  ///< [m] a return at least this far behind the board plane (along its ray), or none, is seen through the board (delta_discont,l; paper 0.5), > 0
    double azimuth_step = 0.0;       ///< [rad] horizontal resolution; 0 = estimate per ring (median)
    double gap_factor = 1.5;         ///< a neighbour farther than this many steps is "no return" (inf), > 1
    int max_stray_points = 2;        ///< a run of at most this many board returns between see-through gaps is a stray return (mixed return, hole wall; so is any run narrower than half the board's narrowest strip), >= 0
    double hole_gap_tolerance = 0.3;  ///< a see-through gap is a hole crossing only if no wider than the hole diameter times (1 + this) plus two azimuth steps, >= 0
    int max_ring_edges = 4;          ///< rings with more hole edges than this are dropped as unreadable (2 per hole crossed), >= 2
    EdgePlacement placement = EdgePlacement::Midpoint;  ///< see EdgePlacement

    void validate() const;  ///< throws ParamError naming the field
    static Params paper();  ///< LastBoardPoint, delta_discont 0.5 m; otherwise as the defaults
  };

  /// Counts after each step, for diagnostics.
  struct Counts {
    std::size_t rings = 0;            ///< rings with at least one board point
    std::size_t board_points = 0;     ///< finite plane inliers
    std::size_t stray_points = 0;     ///< board returns dropped as strays between see-through gaps
    std::size_t hole_crossings = 0;   ///< see-through gaps classified as hole crossings
    std::size_t wide_gaps = 0;        ///< see-through gaps too wide for a hole
    std::size_t occlusions = 0;       ///< gaps where something in front hides the board
    std::size_t border_points = 0;    ///< ring ends on the board's outer border (never edges)
    std::size_t rings_kept = 0;       ///< rings that gave hole edges
    std::size_t rings_rejected = 0;   ///< rings with more hole edges than max_ring_edges
  };

  struct Result {
    bool found = false;
    std::string reason;                  ///< why no edges were found; empty on success
    std::vector<Eigen::Vector3d> edges;  ///< [m] edge points, lidar frame
    std::vector<std::uint16_t> rings;    ///< ring of each edge point
    std::vector<std::size_t> sources;    ///< index (into the input cloud) of each edge's board point
    std::vector<RimCrossing> crossings;  ///< the interval each edge lies in, one per edge (on `plane`)
    Counts counts;
  };

  // Two constructors rather than `Params params = {}`: a nested struct's default
  // member initialisers are not usable in a default argument of its enclosing class.
  DiscontinuityFilter();
  explicit DiscontinuityFilter(Params params);

  /// `cloud`: the pass-through-filtered sweep with `ring` filled (any order,
  /// NaN allowed); `plane`: the board plane; `board_inliers`: indices into
  /// `cloud` of the board's points (a PlaneCandidate's inliers); `target`:
  /// the hole size that bounds a hole crossing. A cloud without rings or a
  /// plane that is not finite is a reason in the result; throws ParamError
  /// for a ring field of another length than the points or an inlier index
  /// past the cloud.
  Result filter(const LidarCloud& cloud, const Plane& plane, const std::vector<std::size_t>& board_inliers,
                const Target& target = Target{}) const;
  const Params& params() const { return params_; }

 private:
  Params params_;
};

}  // namespace l2s
