#pragma once
// Beam tables of the multi-layer lidars the paper's test suite models
// (Velodyne VLP-16, HDL-32E, HDL-64E), from the manufacturers' data sheets.

#include <string>
#include <vector>

namespace l2s::sim {

/// A spinning multi-beam lidar: one elevation per laser, a fixed azimuth step
/// over a full 360 deg sweep, a usable range interval and the range noise.
struct LidarModel {
  std::string name;                ///< "vlp16", "hdl32" or "hdl64"
  std::vector<double> elevations;  ///< [rad] per ring, ring 0 = lowest beam, ascending
  double azimuth_step = 0.0;       ///< [rad] between consecutive firings of one laser (2 pi / whole number)
  double min_range = 0.5;          ///< [m] returns closer than this are dropped
  double max_range = 100.0;        ///< [m] returns farther than this are dropped
  double range_sigma0 = 0.008;     ///< [m] range noise at noise factor K = 1 (paper, Sec. IV-B)

  int rings() const { return static_cast<int>(elevations.size()); }
  /// Firings per laser and sweep: round(2 pi / azimuth_step).
  int azimuth_count() const;

  /// VLP-16: -15..+15 deg every 2 deg, 0.2 deg azimuth step, 0.5..100 m.
  static LidarModel vlp16();
  /// HDL-32E: -30.67..+10.67 deg every 4/3 deg, 0.16 deg azimuth step, 0.5..100 m.
  static LidarModel hdl32();
  /// HDL-64E: upper block +2..-8.33 deg every 1/3 deg, lower block -8.83..-24.33 deg
  /// every 0.5 deg, 0.17 deg azimuth step, 0.9..120 m.
  static LidarModel hdl64();
  /// "vlp16" | "hdl32" | "hdl64"; throws ParamError("lidar", ...) otherwise.
  static LidarModel by_name(const std::string& name);

  /// Throws ParamError naming the field when the table is unusable.
  void validate() const;
};

}  // namespace l2s::sim
