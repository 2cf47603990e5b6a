#pragma once
// Board plane segmentation (paper Sec. III-B): a RANSAC plane parallel to the
// sensor's vertical axis, chosen among several candidates by the board's size.

#include <l2s/geometry.hpp>
#include <l2s/target.hpp>

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace l2s {

/// One plane the segmenter extracted, and why it was or was not the board.
struct PlaneCandidate {
  Plane plane;                  ///< fitted plane, sensor frame
  std::size_t support = 0;      ///< full-cloud points within distance_threshold
  std::size_t patch_points = 0;  ///< points of its largest connected patch
  double extent_long = 0.0;     ///< [m] longer side of the patch's smallest in-plane rectangle
  double extent_short = 0.0;    ///< [m] shorter side
  bool accepted = false;
  std::string reason;           ///< why it was rejected; empty when accepted
};

/// Finds the calibration board's plane in a lidar or stereo cloud.
class PlaneSegmenter {
 public:
  struct Params {
    double distance_threshold = 0.01;  ///< [m] RANSAC consensus distance (paper delta_plane), 0.001..0.1
    double inlier_threshold = 0.05;    ///< [m] final inlier distance (delta_inliers: lidar 0.05, stereo 0.10)
    double max_angle = 0.55;           ///< [rad] max tilt of the plane from the vertical axis (alpha_plane), 0..pi/2
    Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();  ///< sensor "up": lidar +z, camera optical -y; any non-zero
    int max_iterations = 1000;         ///< RANSAC hypotheses per candidate, >= 1
    int max_candidates = 6;            ///< planes extracted before giving up, >= 1
    std::size_t min_support = 30;      ///< fewest consensus points for a candidate, >= 3
    std::size_t max_samples = 50000;   ///< points scored per hypothesis (random subset), >= 100
    double sample_radius = 0.5;        ///< [m] 2nd/3rd sample points come from this neighbourhood, > 0
    double patch_gap_horizontal = 0.3;  ///< [m] in-plane horizontal gap bridged by a patch (> hole diameter), > 0
    double patch_gap_vertical = 0.25;  ///< [m] patch grid cell height: rows this close always join, rows 2x apart never (so the ground 0.5 m below stays apart); >= ring spacing at the board (16 beams: to 7 m), > 0
    double size_tolerance = 0.2;       ///< relative tolerance on the board's width/height, 0..1
    double min_height_fraction = 0.15;  ///< patch height must reach this fraction of the board height, 0..1
    std::uint64_t seed = 42;           ///< random generator seed; same seed, same result

    void validate() const;  ///< throws ParamError naming the field
    static Params lidar();   ///< paper values for a lidar cloud (= defaults)
    static Params stereo();  ///< paper values for a stereo cloud (optical frame, delta_inliers 0.10)
  };

  struct Result {
    bool found = false;
    std::string reason;                 ///< why no board plane was found; empty on success
    Plane plane;                         ///< board plane (least-squares refit), normal towards the sensor
    std::vector<std::size_t> inliers;    ///< input indices within inlier_threshold on the board patch
    double rms = 0.0;                    ///< [m] rms distance of the refit's consensus points
    std::vector<PlaneCandidate> candidates;  ///< in extraction order; the accepted one is last
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
