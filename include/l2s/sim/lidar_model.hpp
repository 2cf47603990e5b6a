#pragma once
// The lidars the simulator models, from the manufacturers' data sheets:
// spinning multi-beam lidars with one scan ring per laser (Velodyne VLP-16,
// HDL-32E, HDL-64E) and ring-free solid-state lidars with a non-repetitive
// rosette scan (Livox Avia- and Mid-360-like).

#include <l2s/export.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace l2s::sim {

/// How the sensor sweeps its beams over the scene.
enum class ScanPattern : std::uint8_t {
  Spinning = 0,  ///< a column of lasers turns about z: one scan ring per laser
  Rosette = 1,   ///< Risley-prism rosette: non-repetitive, no rings
};

/// Which echo a firing reports when its footprint sees several surfaces.
enum class ReturnMode : std::uint8_t { Strongest = 0, Last = 1, First = 2 };

/// "strongest" | "last" | "first"; throws ParamError(field, ...) otherwise.
L2S_SIM_EXPORT ReturnMode return_mode_from_name(const std::string& name, const std::string& field = "return_mode");
L2S_SIM_EXPORT const char* return_mode_name(ReturnMode mode);

/// What one firing illuminates (data sheet). Used only when the simulator's
/// beam footprint is on; the ideal lidar of the paper casts one exact ray.
struct BeamOptics {
  double divergence_horizontal = 0.0;  ///< [rad] full angle (1/e^2) across the scan direction, >= 0
  double divergence_vertical = 0.0;    ///< [rad] full angle (1/e^2) along the vertical, >= 0
  double exit_diameter = 0.0;          ///< [m] beam diameter at the window, >= 0
  double range_resolution = 1.0;       ///< [m] echoes closer than this merge into one, > 0
};

/// Non-repetitive rosette scan: each laser is deflected by two prisms turning
/// in opposite directions at incommensurate rates, so the pattern never
/// repeats and the covered share of the field of view grows with time. With
/// `rotation_rate` > 0 the whole head also turns (360 deg sensors).
struct L2S_SIM_EXPORT RosetteScan {
  double azimuth_half_width = 0.0;  ///< [rad] rosette reach left/right of its centre, > 0
  double elevation_min = 0.0;       ///< [rad] lowest elevation of the field of view
  double elevation_max = 0.0;       ///< [rad] highest, > elevation_min
  double point_rate = 0.0;          ///< [1/s] firings per second over all lasers, > 0
  double frame_period = 0.1;        ///< [s] one simulated frame, > 0
  int lasers = 1;                   ///< lasers firing in turn, each with its own prism phase, >= 1
  double prism_rate_a = 0.0;        ///< [rad/s] first prism's turn rate, > 0
  double prism_rate_b = 0.0;        ///< [rad/s] second prism's (counter-turning), > 0, != a
  double rotation_rate = 0.0;       ///< [rad/s] head rotation about z; 0 = fixed head

  /// Firings in one frame: round(point_rate * frame_period).
  int shots_per_frame() const;
  /// Where a direction ([rad], sensor frame) sits in the field of view: 1 on
  /// its outline, below 1 inside, above 1 outside. A fixed head's field of
  /// view is an ellipse in azimuth and elevation; a turning head's is the
  /// band between its elevations, whatever the azimuth.
  double field_of_view_position(double azimuth, double elevation) const;
};

/// A lidar type: its scan pattern, beam table or rosette, range limits,
/// range noise and beam optics; optionally one unit's per-laser calibration.
struct L2S_SIM_EXPORT LidarModel {
  std::string name;                 ///< "vlp16", "hdl32", "hdl64", "avia" or "mid360"
  ScanPattern pattern = ScanPattern::Spinning;
  std::vector<double> elevations;   ///< [rad] spinning: per ring, ring 0 = lowest beam, ascending
  double azimuth_step = 0.0;        ///< [rad] spinning: between firings of one laser (2 pi / whole number)
  RosetteScan rosette;              ///< rosette pattern only
  double min_range = 0.5;           ///< [m] returns closer than this are dropped
  double max_range = 100.0;         ///< [m] returns farther than this are dropped
  double range_sigma0 = 0.008;      ///< [m] range noise at noise factor K = 1 (paper, Sec. IV-B)
  BeamOptics optics;                ///< data-sheet footprint (simulated only when asked)

  /// One unit's calibration table, one entry per ring, like a Velodyne
  /// calibration file; empty = ideal lasers exactly on the nominal table.
  struct LaserCorrection {
    double elevation = 0.0;          ///< [rad] true elevation minus nominal
    double azimuth = 0.0;            ///< [rad] beam azimuth minus encoder azimuth (rotational correction)
    double vertical_offset = 0.0;    ///< [m] beam origin from the sensor origin, perpendicular to the beam, upwards
    double horizontal_offset = 0.0;  ///< [m] beam origin from the sensor origin, perpendicular to the beam, to its left
  };
  std::vector<LaserCorrection> corrections;

  bool has_rings() const { return pattern == ScanPattern::Spinning; }
  /// Lasers of a spinning model (scan rings); 0 for a rosette.
  int rings() const { return static_cast<int>(elevations.size()); }
  /// Spinning: firings per laser and sweep, round(2 pi / azimuth_step).
  int azimuth_count() const;

  /// VLP-16: -15..+15 deg every 2 deg, 0.2 deg azimuth step, 0.5..100 m.
  static LidarModel vlp16();
  /// HDL-32E: -30.67..+10.67 deg every 4/3 deg, 0.16 deg azimuth step, 0.5..100 m.
  static LidarModel hdl32();
  /// HDL-64E: upper block +2..-8.33 deg every 1/3 deg, lower block -8.83..-24.33 deg
  /// every 0.5 deg, 0.17 deg azimuth step, 0.9..120 m.
  static LidarModel hdl64();
  /// Livox Avia-like: rosette over 70.4 x 77.2 deg, 240k points/s, six
  /// lasers, 1..190 m, 2 cm range noise, 0.03 x 0.28 deg divergence.
  static LidarModel avia();
  /// Livox Mid-360-like: 360 deg x -7..+52 deg, 200k points/s, four lasers
  /// on a turning head, 0.1..40 m, 2 cm range noise.
  static LidarModel mid360();
  /// "vlp16" | "hdl32" | "hdl64" | "avia" | "mid360"; throws ParamError("lidar", ...) otherwise.
  static LidarModel by_name(const std::string& name);
  /// The names by_name accepts.
  static std::vector<std::string> names();

  /// Throws ParamError naming the field when the model is unusable.
  void validate() const;
};

}  // namespace l2s::sim
