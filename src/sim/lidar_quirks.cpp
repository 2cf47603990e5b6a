// Per-laser calibration tables drawn like real ones. The spreads follow what
// Velodyne calibration files hold (vertical/horizontal offset corrections,
// vertical and rotational corrections per laser); the drivers turn them into
// exact points, so the errors show only as beam geometry: lasers that start
// off the sensor origin and fire at irregular elevations and azimuths.

#include <l2s/sim/lidar_quirks.hpp>

#include <l2s/error.hpp>

#include "sim/random.hpp"

#include <algorithm>
#include <cmath>

namespace l2s::sim {
namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

/// Independent draws for one table: uniform and normal by (laser, quantity).
class TableDraw {
 public:
  explicit TableDraw(std::uint64_t seed) : seed_(seed) {}
  double uniform(int laser, int what, double lo, double hi) const {
    return lo + (hi - lo) * detail::uniform01(detail::hash_counters(seed_, 0x7AB1E, laser, what));
  }
  double normal(int laser, int what, double sigma) const {
    return sigma * detail::standard_normal(detail::hash_counters(seed_, 0x7AB1E, laser, what + 100));
  }
  double sign(int what) const { return uniform(-1, what, 0.0, 1.0) < 0.5 ? -1.0 : 1.0; }

 private:
  std::uint64_t seed_;
};

enum Quantity { kVertical = 1, kHorizontal = 2, kElevation = 3, kAzimuth = 4, kCommon = 5 };

/// Elevation errors, clamped to 40 % of the gap to each neighbour so that the
/// lasers keep their order (ring 0 stays the lowest beam).
void add_elevation_errors(const LidarModel& model, const TableDraw& draw, double sigma,
                          std::vector<LidarModel::LaserCorrection>* table) {
  const int n = model.rings();
  for (int k = 0; k < n; ++k) {
    double room = 1.0;
    if (k > 0) room = std::min(room, model.elevations[k] - model.elevations[k - 1]);
    if (k + 1 < n) room = std::min(room, model.elevations[k + 1] - model.elevations[k]);
    (*table)[k].elevation = std::clamp(draw.normal(k, kElevation, sigma), -0.4 * room, 0.4 * room);
  }
}

}  // namespace

LidarQuirks LidarQuirks::all(std::uint64_t table_seed) {
  LidarQuirks quirks;
  quirks.laser_table = true;
  quirks.beam_footprint = true;
  quirks.table_seed = table_seed;
  return quirks;
}

std::vector<LidarModel::LaserCorrection> draw_laser_table(const LidarModel& model, std::uint64_t seed) {
  if (!model.has_rings()) throw ParamError("lidar", "a rosette lidar '" + model.name + "' has no laser table");
  const TableDraw draw(seed);
  const int n = model.rings();
  std::vector<LidarModel::LaserCorrection> table(static_cast<std::size_t>(n));
  if (model.name == "hdl64") {
    // The frame origin sits at the upper block's optical centre; the lower
    // block fires from 5-7 cm below it.
    for (int k = 0; k < n; ++k) {
      const bool upper = k >= n / 2;
      table[k].vertical_offset = draw.uniform(k, kVertical, -0.01, 0.01) + (upper ? 0.0 : -0.06);
      table[k].horizontal_offset = (k % 2 == 0 ? 0.026 : -0.026) + draw.normal(k, kHorizontal, 0.0015);
      table[k].azimuth = draw.uniform(k, kAzimuth, -0.1, 0.1);
    }
    add_elevation_errors(model, draw, 0.1 * kDeg, &table);
  } else if (model.name == "hdl32") {
    const double common = draw.sign(kCommon) * draw.uniform(-1, kCommon, 0.005, 0.02);
    for (int k = 0; k < n; ++k) {
      table[k].vertical_offset = common + draw.normal(k, kVertical, 0.003);
      table[k].azimuth = draw.normal(k, kAzimuth, 0.1 * kDeg);
    }
    add_elevation_errors(model, draw, 0.05 * kDeg, &table);
  } else {
    // VLP-16-like: a common offset of the unit plus the optics' tilt pattern.
    const double common = draw.sign(kCommon) * draw.uniform(-1, kCommon, 0.015, 0.04);
    for (int k = 0; k < n; ++k) {
      const double optics = -0.75e-3 * model.elevations[k] / kDeg;
      table[k].vertical_offset = common + optics + draw.normal(k, kVertical, 0.001);
      table[k].azimuth = draw.normal(k, kAzimuth, 0.05 * kDeg);
    }
    add_elevation_errors(model, draw, 0.03 * kDeg, &table);
  }
  return table;
}

LidarModel with_quirks(LidarModel model, const LidarQuirks& quirks) {
  if (quirks.laser_table && model.has_rings()) model.corrections = draw_laser_table(model, quirks.table_seed);
  return model;
}

}  // namespace l2s::sim
