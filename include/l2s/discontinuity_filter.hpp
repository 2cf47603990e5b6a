#pragma once
// Lidar depth discontinuities on the board (paper Sec. III-B, after Levinson
// and Thrun 2013) and the ring filter of Sec. III-C: the points where a ring
// leaves the board through a hole, as edge points for the circle finder.

#include <l2s/geometry.hpp>
#include <l2s/types.hpp>

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace l2s {

/// Finds the hole edges of the board along each lidar ring.
class DiscontinuityFilter {
 public:
  /// Where an edge point is placed.
  enum class EdgePlacement {
    LastBoardPoint,  ///< the last board return before the jump (paper)
    Midpoint,        ///< the board plane hit by the ray halfway (in azimuth) to the next return
  };

  struct Params {
    double min_discontinuity = 0.5;  ///< [m] range jump p_delta that marks an edge (delta_discont,l), > 0
    double azimuth_step = 0.0;       ///< [rad] horizontal resolution; 0 = estimate per ring (median)
    double gap_factor = 1.5;         ///< a neighbour farther than this many steps is "no return" (inf), > 1
    bool drop_border_points = true;  ///< drop the first/last board point of each ring (board outline)
    int min_ring_edges = 2;          ///< a ring keeps its edges only with this many after border removal, >= 1
    int max_ring_edges = 4;          ///< ... and at most this many (2 per hole crossed), >= min_ring_edges
    EdgePlacement placement = EdgePlacement::Midpoint;  ///< see EdgePlacement

    void validate() const;  ///< throws ParamError naming the field
    static Params paper();  ///< LastBoardPoint; otherwise as the defaults
  };

  /// Counts after each step, for diagnostics.
  struct Counts {
    std::size_t rings = 0;            ///< rings with at least one board point
    std::size_t board_points = 0;     ///< finite plane inliers
    std::size_t discontinuities = 0;  ///< board points with p_delta >= min_discontinuity
    std::size_t border_points = 0;    ///< of those, dropped as first/last of a ring's board segment
    std::size_t rings_kept = 0;       ///< rings whose edge count fits a circle
    std::size_t rings_rejected = 0;   ///< rings with edges, but a count that does not
  };

  struct Result {
    bool found = false;
    std::string reason;                  ///< why no edges were found; empty on success
    std::vector<Eigen::Vector3d> edges;  ///< [m] edge points, lidar frame
    std::vector<std::uint16_t> rings;    ///< ring of each edge point
    std::vector<std::size_t> sources;    ///< index (into the input cloud) of each edge's board point
    Counts counts;
  };

  // Two constructors rather than `Params params = {}`: a nested struct's default
  // member initialisers are not usable in a default argument of its enclosing class.
  DiscontinuityFilter();
  explicit DiscontinuityFilter(Params params);

  /// `cloud`: the pass-through-filtered sweep with `ring` filled (any order,
  /// NaN allowed); `plane`: the board plane; `board_inliers`: indices into
  /// `cloud` of the board's points (PlaneSegmenter::Result::inliers).
  Result filter(const LidarCloud& cloud, const Plane& plane,
                const std::vector<std::size_t>& board_inliers) const;
  const Params& params() const { return params_; }

 private:
  Params params_;
};

}  // namespace l2s
