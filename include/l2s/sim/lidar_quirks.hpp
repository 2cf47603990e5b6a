#pragma once
// How a real lidar departs from the ideal one of the paper's simulation:
// per-laser calibration errors like those of a Velodyne calibration table
// (vertical and horizontal beam origin offsets, elevation and azimuth
// corrections), and beam divergence (a footprint that mixes the echoes of
// several surfaces at depth edges). All off by default.

#include <l2s/export.hpp>
#include <l2s/sim/lidar_model.hpp>

#include <cstdint>
#include <vector>

namespace l2s::sim {

/// Which quirks a simulated lidar shows.
struct L2S_SIM_EXPORT LidarQuirks {
  bool laser_table = false;     ///< spinning models: per-laser offsets and angle errors drawn like a real table
  bool beam_footprint = false;  ///< divergence: mixed returns at depth edges, holes that look smaller
  ReturnMode return_mode = ReturnMode::Strongest;  ///< the echo reported when a footprint sees several surfaces
  std::uint64_t table_seed = 1;  ///< draws the laser table: one seed, one sensor unit

  /// Every quirk on, strongest return.
  static LidarQuirks all(std::uint64_t table_seed = 1);
  bool any() const { return laser_table || beam_footprint; }
};

/// One unit's calibration table for a spinning model, drawn (deterministically
/// from `seed`) with the spread of real tables:
/// - vlp16: every beam starts 1.5-4 cm above or below the axis (one sign per
///   unit) plus the optics' -0.75 mm/deg of elevation, +-1 mm; elevation
///   errors 0.03 deg, azimuth corrections 0.05 deg (1 sigma).
/// - hdl32: origins 0.5-2 cm off (one sign per unit) +-3 mm; 0.05 / 0.1 deg.
/// - hdl64: upper-block lasers within +-1 cm of the origin, lower-block ones
///   5-7 cm below it, +-2.6 cm alternating sideways, azimuth corrections up
///   to +-0.1 rad, elevation errors 0.1 deg (kept in ascending order).
/// - any other spinning model: as vlp16.
/// Throws ParamError("lidar", ...) for a rosette model.
L2S_SIM_EXPORT std::vector<LidarModel::LaserCorrection> draw_laser_table(const LidarModel& model, std::uint64_t seed);

/// `model` as one real unit: its drawn laser table when quirks.laser_table is
/// on (spinning models; a rosette lidar has one beam origin and no table).
L2S_SIM_EXPORT LidarModel with_quirks(LidarModel model, const LidarQuirks& quirks);

}  // namespace l2s::sim
