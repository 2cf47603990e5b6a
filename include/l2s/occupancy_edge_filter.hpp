#pragma once
// Hole rims of a dense board cloud: the ring-free counterpart of the
// DiscontinuityFilter. A solid-state lidar with a non-repetitive scan
// (Livox-like) has no rings to walk along, but a static board accumulated for
// a second or two is covered densely. Its points, seen in the board plane,
// form an occupancy image: places a radius away from any board point, with
// board all around, are the holes' centres; the board points bordering them
// are the rims. A hole that the field of view's edge runs through is open on
// one side: two holes found at the pattern's spacing predict it.

#include <l2s/export.hpp>
#include <l2s/geometry.hpp>
#include <l2s/target.hpp>

#include <Eigen/Core>
#include <cstddef>
#include <string>
#include <vector>

namespace l2s {

/// Thread safety: holds only what it was built with; its const functions may
/// run concurrently on one instance, and each call is deterministic (random
/// draws are seeded per call from the params).
class L2S_EXPORT OccupancyEdgeFilter {
 public:
  struct Params {
    double cell_factor = 1.0;    ///< grid cell = this x the board points' mean spacing (from their density), > 0
    double min_cell = 0.004;     ///< [m] smallest cell, > 0
    double max_cell = 0.04;      ///< [m] largest cell (a sparser board cannot show its holes), >= min_cell
    double min_hole_depth = 0.5;  ///< a hole's centre is at least this many radii from every board point (in the grid), (0, 1.5)
    int rim_sectors = 90;        ///< directions around each hole; the innermost board point of each is a rim point, >= 8

    void validate() const;  ///< throws ParamError naming the field
  };

  struct Result {
    bool found = false;
    std::string reason;                  ///< why no rims were found; empty on success
    std::vector<Eigen::Vector3d> edges;  ///< [m] rim points, sensor frame (board returns)
    std::size_t board_points = 0;        ///< board points used
    double cell = 0.0;                   ///< [m] occupancy cell
    /// When no hole was found and the board's points lie too far apart to
    /// show holes of the target's radius: how many times as many points
    /// (sweeps of the static board) it takes, > 1; else 0.
    double sparse_factor = 0.0;
    /// Places found deep enough and surrounded by board, and those the hole
    /// pattern predicts that show a rim arc.
    int holes = 0;
    /// [m] the board points' extent in the plane, along the sensor's
    /// horizontal and up: less than the board's when the field of view's
    /// edge (or something in front) cuts it.
    double seen_width = 0.0, seen_height = 0.0;

    /// When fewer than four holes were found on a board seen cut short: why,
    /// in words for the user (which size was seen, what to do); else empty.
    std::string cut_board_hint(const Target& target) const;
  };

  // Two constructors rather than `Params params = {}` (see PlaneSegmenter).
  OccupancyEdgeFilter();
  explicit OccupancyEdgeFilter(Params params);

  /// `points`: the (accumulated) cloud, sensor frame; `plane`: the board
  /// plane; `board_inliers`: indices of the board's points; `up`: the
  /// sensor's up axis (the occupancy grid is aligned with it). Throws
  /// ParamError for an inlier index past the points.
  Result filter(const std::vector<Eigen::Vector3d>& points, const Plane& plane,
                const std::vector<std::size_t>& board_inliers, const Eigen::Vector3d& up,
                const Target& target = Target{}) const;
  const Params& params() const { return params_; }

 private:
  Params params_;
};

}  // namespace l2s
