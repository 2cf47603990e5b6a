// Lidar tables from the data sheets. Beam optics: Velodyne gives 3.0 mrad
// (horizontal) x 1.5 mrad (vertical) divergence for its current sensors (VLP-16
// and VLS-128 manuals) and records two echoes only when they are at least 1 m
// apart; we use both for all three Velodyne models. Livox gives 0.03 x 0.28 deg
// divergence and 2 cm range noise (1 sigma) for the Avia and its siblings; the
// exit diameters and the Livox echo separation are our assumptions.

#include <l2s/sim/lidar_model.hpp>

#include <l2s/error.hpp>

#include <cmath>

namespace l2s::sim {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;

/// `count` elevations from `lowest_deg` upwards in steps of `step_deg`.
std::vector<double> evenly_spaced(double lowest_deg, double step_deg, int count) {
  std::vector<double> elevations;
  for (int i = 0; i < count; ++i) elevations.push_back((lowest_deg + i * step_deg) * kDeg);
  return elevations;
}

BeamOptics velodyne_optics(double exit_diameter) {
  BeamOptics optics;
  optics.divergence_horizontal = 3.0e-3;
  optics.divergence_vertical = 1.5e-3;
  optics.exit_diameter = exit_diameter;
  optics.range_resolution = 1.0;
  return optics;
}

BeamOptics livox_optics() {
  BeamOptics optics;
  optics.divergence_horizontal = 0.03 * kDeg;
  optics.divergence_vertical = 0.28 * kDeg;
  optics.exit_diameter = 0.005;
  optics.range_resolution = 0.6;
  return optics;
}

}  // namespace

ReturnMode return_mode_from_name(const std::string& name, const std::string& field) {
  if (name == "strongest") return ReturnMode::Strongest;
  if (name == "last") return ReturnMode::Last;
  if (name == "first") return ReturnMode::First;
  throw ParamError(field, "unknown return mode '" + name + "' (expected strongest, last or first)");
}

const char* return_mode_name(ReturnMode mode) {
  switch (mode) {
    case ReturnMode::Strongest: return "strongest";
    case ReturnMode::Last: return "last";
    case ReturnMode::First: return "first";
  }
  return "strongest";
}

int RosetteScan::shots_per_frame() const {
  return static_cast<int>(std::lround(point_rate * frame_period));
}

double RosetteScan::field_of_view_position(double azimuth, double elevation) const {
  const double from_middle =
      std::abs(elevation - 0.5 * (elevation_max + elevation_min)) / (0.5 * (elevation_max - elevation_min));
  return rotation_rate > 0.0 ? from_middle : std::hypot(azimuth / azimuth_half_width, from_middle);
}

int LidarModel::azimuth_count() const {
  return static_cast<int>(std::lround(2.0 * kPi / azimuth_step));
}

LidarModel LidarModel::vlp16() {
  LidarModel m;
  m.name = "vlp16";
  m.elevations = evenly_spaced(-15.0, 2.0, 16);
  m.azimuth_step = 0.2 * kDeg;
  m.min_range = 0.5;
  m.max_range = 100.0;
  m.optics = velodyne_optics(0.011);  // 9.5 x 12.7 mm spot at the window
  return m;
}

LidarModel LidarModel::hdl32() {
  LidarModel m;
  m.name = "hdl32";
  // -30.67 .. +10.67 deg: 32 beams 4/3 deg apart.
  m.elevations = evenly_spaced(-30.67, 4.0 / 3.0, 32);
  m.azimuth_step = 0.16 * kDeg;
  m.min_range = 0.5;
  m.max_range = 100.0;
  m.optics = velodyne_optics(0.010);
  return m;
}

LidarModel LidarModel::hdl64() {
  LidarModel m;
  m.name = "hdl64";
  // Lower block: -24.33 .. -8.83 deg every 0.5 deg; upper block: -8.33 .. +2.0
  // deg every 1/3 deg. Ring 0 is the lowest beam, so the lower block comes first.
  m.elevations = evenly_spaced(-24.33, 0.5, 32);
  const std::vector<double> upper = evenly_spaced(-8.33, 1.0 / 3.0, 32);
  m.elevations.insert(m.elevations.end(), upper.begin(), upper.end());
  // 0.17 deg nominal; a whole number of firings per turn (2118) keeps sweeps seamless.
  m.azimuth_step = 2.0 * kPi / 2118.0;
  m.min_range = 0.9;
  m.max_range = 120.0;
  m.optics = velodyne_optics(0.010);
  return m;
}

LidarModel LidarModel::avia() {
  LidarModel m;
  m.name = "avia";
  m.pattern = ScanPattern::Rosette;
  RosetteScan& r = m.rosette;
  r.azimuth_half_width = 0.5 * 70.4 * kDeg;
  r.elevation_min = -0.5 * 77.2 * kDeg;
  r.elevation_max = 0.5 * 77.2 * kDeg;
  r.point_rate = 240000.0;
  r.lasers = 6;
  // 400 passes through the centre per second and laser, each turned by an
  // irrational share of a half turn against the one before.
  r.prism_rate_a = 2.0 * kPi * 230.9;
  r.prism_rate_b = 2.0 * kPi * 169.1;
  m.min_range = 1.0;
  m.max_range = 190.0;
  m.range_sigma0 = 0.02;
  m.optics = livox_optics();
  return m;
}

LidarModel LidarModel::mid360() {
  LidarModel m;
  m.name = "mid360";
  m.pattern = ScanPattern::Rosette;
  RosetteScan& r = m.rosette;
  r.azimuth_half_width = 4.0 * kDeg;
  r.elevation_min = -7.0 * kDeg;
  r.elevation_max = 52.0 * kDeg;
  r.point_rate = 200000.0;
  r.lasers = 4;
  r.prism_rate_a = 2.0 * kPi * 183.7;
  r.prism_rate_b = 2.0 * kPi * 116.3;
  // Not one turn per frame: the head turns by a golden-ratio share of a petal
  // more each turn, so successive turns interleave their sweeps evenly and
  // the coverage fills in over a second or two, as a non-repetitive scan does.
  r.rotation_rate = 2.0 * kPi * (183.7 + 116.3) / (29.0 + 0.6180339887);
  m.min_range = 0.1;
  m.max_range = 40.0;
  m.range_sigma0 = 0.02;
  m.optics = livox_optics();
  return m;
}

std::vector<std::string> LidarModel::names() { return {"vlp16", "hdl32", "hdl64", "avia", "mid360"}; }

LidarModel LidarModel::by_name(const std::string& name) {
  if (name == "vlp16") return vlp16();
  if (name == "hdl32") return hdl32();
  if (name == "hdl64") return hdl64();
  if (name == "avia") return avia();
  if (name == "mid360") return mid360();
  throw ParamError("lidar", "unknown model '" + name + "' (expected vlp16, hdl32, hdl64, avia or mid360)");
}

namespace {

void validate_spinning(const LidarModel& m) {
  if (m.elevations.empty()) throw ParamError("lidar.elevations", "no beams");
  for (std::size_t i = 1; i < m.elevations.size(); ++i)
    if (!(m.elevations[i] > m.elevations[i - 1]))
      throw ParamError("lidar.elevations", "must be strictly ascending (ring 0 = lowest)");
  if (!(m.azimuth_step > 1e-5 && m.azimuth_step < 0.1))
    throw ParamError("lidar.azimuth_step", "must be in (1e-5, 0.1) rad");
  if (!m.corrections.empty() && m.corrections.size() != m.elevations.size())
    throw ParamError("lidar.corrections", "must be empty or hold one entry per ring");
  for (const LidarModel::LaserCorrection& c : m.corrections)
    for (double v : {c.elevation, c.azimuth, c.vertical_offset, c.horizontal_offset})
      if (!(std::abs(v) < 0.5)) throw ParamError("lidar.corrections", "must be finite and below 0.5 (rad or m)");
}

void validate_rosette(const RosetteScan& r) {
  if (!(r.azimuth_half_width > 0.0 && r.azimuth_half_width <= kPi))
    throw ParamError("lidar.rosette.azimuth_half_width", "must be in (0, pi] rad");
  if (!(r.elevation_min >= -0.5 * kPi && r.elevation_max <= 0.5 * kPi && r.elevation_max > r.elevation_min))
    throw ParamError("lidar.rosette.elevation_max", "must exceed elevation_min, both within +-pi/2");
  if (!(r.point_rate > 0.0 && r.point_rate <= 1e7)) throw ParamError("lidar.rosette.point_rate", "must be in (0, 1e7] 1/s");
  if (!(r.frame_period > 0.0 && r.frame_period <= 10.0))
    throw ParamError("lidar.rosette.frame_period", "must be in (0, 10] s");
  if (r.shots_per_frame() < 1) throw ParamError("lidar.rosette.point_rate", "gives no firing per frame");
  if (r.lasers < 1 || r.lasers > 64) throw ParamError("lidar.rosette.lasers", "must be 1..64");
  if (!(r.prism_rate_a > 0.0 && r.prism_rate_b > 0.0 && r.prism_rate_a != r.prism_rate_b))
    throw ParamError("lidar.rosette.prism_rate_b", "prism rates must be > 0 and differ");
  if (!(r.rotation_rate >= 0.0)) throw ParamError("lidar.rosette.rotation_rate", "must be >= 0");
}

}  // namespace

void LidarModel::validate() const {
  if (pattern == ScanPattern::Spinning) {
    validate_spinning(*this);
  } else {
    validate_rosette(rosette);
    if (!corrections.empty()) throw ParamError("lidar.corrections", "a rosette lidar has no laser table");
  }
  if (!(min_range >= 0.0 && max_range > min_range))
    throw ParamError("lidar.max_range", "must exceed min_range >= 0");
  if (!(range_sigma0 >= 0.0)) throw ParamError("lidar.range_sigma0", "must be >= 0");
  if (!(optics.divergence_horizontal >= 0.0 && optics.divergence_horizontal < 0.1))
    throw ParamError("lidar.optics.divergence_horizontal", "must be in [0, 0.1) rad");
  if (!(optics.divergence_vertical >= 0.0 && optics.divergence_vertical < 0.1))
    throw ParamError("lidar.optics.divergence_vertical", "must be in [0, 0.1) rad");
  if (!(optics.exit_diameter >= 0.0 && optics.exit_diameter < 0.2))
    throw ParamError("lidar.optics.exit_diameter", "must be in [0, 0.2) m");
  if (!(optics.range_resolution > 0.0)) throw ParamError("lidar.optics.range_resolution", "must be > 0 m");
}

}  // namespace l2s::sim
