#pragma once
// Board plane segmentation (paper Sec. III-B): RANSAC planes parallel to the
// sensor's vertical axis, each cut to its largest connected patch; the
// board-sized ones are the hypotheses a branch verifies by their holes, most
// board-like (size, standing apart from its surroundings) first.

#include <l2s/export.hpp>
#include <l2s/geometry.hpp>
#include <l2s/target.hpp>

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace l2s {

/// One plane the segmenter extracted, and whether it may be the board.
struct PlaneCandidate {
  Plane plane;                  ///< fitted plane, sensor frame, normal towards the sensor
  std::size_t support = 0;      ///< full-cloud points within distance_threshold
  std::size_t patch_points = 0;  ///< points of its largest connected patch
  double extent_long = 0.0;     ///< [m] longer side of the patch's smallest in-plane rectangle
  double extent_short = 0.0;    ///< [m] shorter side
  /// Coplanar points just outside the patch, as a density relative to the
  /// patch's own (second-highest of its four sides): ~0 for a board standing
  /// apart, ~1 for a window cut out of a wall.
  double isolation = 0.0;
  double prior = 0.0;           ///< board-likeness before verification, 0..1 (size and isolation)
  bool plausible = false;       ///< board-sized: a hypothesis for the branch to verify
  bool oversized = false;       ///< larger than the board, kept as a last-resort hypothesis (Params::keep_oversized)
  std::string reason;           ///< why it cannot be the board; empty when plausible
  std::vector<std::size_t> inliers;  ///< input indices within inlier_threshold on the patch (plausible or oversized)
  double rms = 0.0;             ///< [m] rms distance of the refit's consensus (plausible or oversized)
};

/// Finds the calibration board's plane in a lidar or stereo cloud.
/// Thread safety: holds only what it was built with; its const functions may
/// run concurrently on one instance, and each call is deterministic (random
/// draws are seeded per call from the params).
class L2S_EXPORT PlaneSegmenter {
 public:
  struct Params {
    double distance_threshold = 0.01;  ///< [m] RANSAC consensus distance (paper delta_plane), 0.001..0.1
    double inlier_threshold = 0.05;    ///< [m] final inlier distance (delta_inliers: lidar 0.05, stereo 0.10)
    double max_angle = 0.55;           ///< [rad] max tilt of the plane from the vertical axis (alpha_plane), 0..pi/2
    Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();  ///< sensor "up": lidar +z, camera optical -y; any non-zero
    int max_iterations = 1000;         ///< RANSAC hypotheses per candidate, >= 1
    int max_candidates = 10;           ///< planes extracted (board-sized or not), >= 1
    std::size_t min_support = 30;      ///< fewest consensus points for a candidate, >= 3
    std::size_t max_samples = 50000;   ///< points scored per hypothesis (random subset), >= 100
    double sample_radius = 0.5;        ///< [m] 2nd/3rd sample points come from this neighbourhood, > 0
    double patch_gap_horizontal = 0.3;  ///< [m] in-plane horizontal gap bridged by a patch (> hole diameter), > 0
    double patch_gap_vertical = 0.25;  ///< [m] patch grid cell height: rows this close always join, rows 2x apart never (so the ground 0.5 m below stays apart); >= ring spacing at the board (16 beams: to 7 m), > 0
    /// Level surfaces (within 30 deg of horizontal: floor, ceiling, table)
    /// taken out before the board is looked for, up to this many, each
    /// holding at least a tenth of the samples. A dense stereo floor is
    /// otherwise cut into slanted planes with what stands on it, candidates
    /// enough to crowd a small board out. 0..4.
    int remove_level_planes = 0;
    double size_tolerance = 0.2;       ///< relative tolerance on the board's width/height (the patch may exceed them by this), 0..1
    /// Patches larger than the board are ranked after every board-sized one
    /// instead of dropped: a coarse stereo cloud merges a board with what
    /// touches it in depth (SGM carries the board's disparity into a plain
    /// wall behind it), and only a finer look at the region can tell.
    bool keep_oversized = false;
    double min_length_fraction = 0.8;  ///< the patch's long side must reach this share of the board's long side (lower for clouds that may see part of it), 0..1
    double min_height_fraction = 0.15;  ///< patch height must reach this fraction of the board height, 0..1
    double isolation_band = 0.2;       ///< [m] width of the band around a patch searched for coplanar points, > 0
    /// [1/m] Stereo clouds: depth noise grows with depth, sigma_z = depth_noise * z^2
    /// (disparity sigma / fx * B; StereoMatcher::Result::depth_noise). The
    /// consensus and inlier thresholds grow to 2 and 3 sigma_z where that is
    /// larger, so one setting fits every rig and distance. 0 = fixed (lidar), >= 0
    double depth_noise = 0.0;
    std::uint64_t seed = 42;           ///< random generator seed; same seed, same result

    void validate() const;  ///< throws ParamError naming the field
    static Params lidar();   ///< paper values for a lidar cloud (= defaults)
    static Params stereo();  ///< paper values for a stereo cloud (optical frame, delta_inliers 0.10)
  };

  struct Result {
    bool found = false;                 ///< at least one plausible candidate
    std::string reason;                 ///< why no candidate is plausible; empty when found
    std::vector<PlaneCandidate> candidates;  ///< in extraction order (decreasing support)
    std::vector<int> ranking;           ///< plausible candidates, most board-like (prior) first
    // The top-ranked candidate, for callers that take it without verifying:
    Plane plane;                         ///< its plane (least-squares refit), normal towards the sensor
    std::vector<std::size_t> inliers;    ///< its inliers (input indices)
    double rms = 0.0;                    ///< [m] its refit rms
  };

  // Two constructors rather than `Params params = {}`: a nested struct's default
  // member initialisers are not usable in a default argument of its enclosing class.
  PlaneSegmenter();
  explicit PlaneSegmenter(Params params);

  /// Non-finite points are ignored. `target` gives the board size to look for.
  Result segment(const std::vector<Eigen::Vector3d>& points, const Target& target = Target{}) const;
  const Params& params() const { return params_; }

 private:
  Params params_;
};

}  // namespace l2s
