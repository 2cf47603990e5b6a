#pragma once
// Synthetic sweeps of spinning lidars whose beams do not start at the sensor
// origin, for the ring-recovery tests and benchmark. Each laser k fires from
// its own origin: `radial` metres out from the axis along the firing azimuth,
// `lateral` metres sideways, and `vertical_offset` metres along the beam's
// normal (as Velodyne calibration tables give vert_offset_correction), so its
// returns lie on z ~ d * tan(elevation) + h_k with h_k = vertical_offset /
// cos(elevation) - radial * tan(elevation). Offsets follow real tables: VLP-16
// vertical corrections +-11.2 mm with its 3.4 cm optical radius; HDL-64E S3
// vert_offset_correction 0.204-0.217 m (upper block) and 0.146-0.163 m (lower
// block), lateral +-0.026 m. Header-only so that the benchmark can use it.

#include <l2s/types.hpp>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <ostream>
#include <random>
#include <set>
#include <string>
#include <vector>

namespace l2s::test {

/// One laser of a spinning lidar.
struct Laser {
  double elevation = 0.0;        ///< [rad] beam elevation
  double vertical_offset = 0.0;  ///< [m] origin offset along the beam's upward normal
  double radial = 0.0;           ///< [m] origin distance from the spin axis
  double lateral = 0.0;          ///< [m] origin offset to the left of the firing direction
};

/// A beam table, ascending elevations (index = laser id = expected ring).
struct LaserTable {
  std::string name;
  std::vector<Laser> lasers;
};

/// Test names print the table's name, not its bytes.
inline void PrintTo(const LaserTable& table, std::ostream* out) { *out << table.name; }

namespace sweep_detail {
constexpr double kDeg = M_PI / 180.0;

inline std::vector<double> degrees_to_radians(std::vector<double> degrees) {
  for (double& d : degrees) d *= kDeg;
  return degrees;
}

// Adds per-laser elevation errors (real tables are not the data sheet's).
inline LaserTable build(const std::string& name, const std::vector<double>& elevations,
                        double angle_error_deg, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> error(0.0, angle_error_deg * kDeg);
  LaserTable table{name, {}};
  for (double e : elevations) table.lasers.push_back({e + error(rng), 0.0, 0.0, 0.0});
  return table;
}
}  // namespace sweep_detail

/// VLP-16: -15..+15 deg every 2 deg; beams 3.4 cm off the axis, vertical
/// corrections -0.75 mm/deg (+11.2 mm at -15 deg).
inline LaserTable vlp16_table(unsigned seed = 1) {
  std::vector<double> e;
  for (int k = 0; k < 16; ++k) e.push_back(-15.0 + 2.0 * k);
  LaserTable table = sweep_detail::build("VLP16", sweep_detail::degrees_to_radians(e), 0.05, seed);
  for (Laser& laser : table.lasers) {
    laser.radial = 0.034;
    laser.vertical_offset = -0.0112 * laser.elevation / (15.0 * sweep_detail::kDeg);
  }
  return table;
}

/// HDL-32E: -30.67..+10.67 deg every 4/3 deg; beams 4 cm off the axis; emitters
/// behind one lens, so vertical offsets fall with elevation (-1 mm/deg, as the
/// VLP-16's), scattered by 2 mm, around a 1 cm mounting offset.
inline LaserTable hdl32e_table(unsigned seed = 2) {
  std::vector<double> e;
  for (int k = 0; k < 32; ++k) e.push_back(-30.67 + 4.0 / 3.0 * k);
  LaserTable table = sweep_detail::build("HDL32E", sweep_detail::degrees_to_radians(e), 0.05, seed);
  std::mt19937 rng(seed + 100);
  std::normal_distribution<double> scatter(0.0, 0.002);
  for (Laser& laser : table.lasers) {
    laser.radial = 0.04;
    laser.vertical_offset = 0.01 - 0.001 * laser.elevation / sweep_detail::kDeg + scatter(rng);
  }
  return table;
}

/// HDL-64E S3: upper block +2..-8.33 deg every 1/3 deg at vert_offset ~0.21 m,
/// lower block -8.83..-24.33 deg every 0.5 deg at ~0.15 m (each a linear trend
/// in elevation as in the S3 tables, plus 1 mm scatter), lateral +-0.026 m.
inline LaserTable hdl64e_table(unsigned seed = 3) {
  std::vector<double> e;
  for (int k = 31; k >= 0; --k) e.push_back(-8.83 - 0.5 * k);  // lower block
  for (int k = 31; k >= 0; --k) e.push_back(2.0 - k / 3.0);    // upper block
  LaserTable table = sweep_detail::build("HDL64E", sweep_detail::degrees_to_radians(e), 0.03, seed);
  std::mt19937 rng(seed + 100);
  std::normal_distribution<double> scatter(0.0, 0.001);
  for (std::size_t k = 0; k < table.lasers.size(); ++k) {
    Laser& laser = table.lasers[k];
    const bool upper = k >= 32;
    laser.vertical_offset =
        (upper ? 0.2066 : 0.1331) - (upper ? 0.0727 : 0.0687) * laser.elevation + scatter(rng);
    laser.lateral = k % 2 ? 0.026 : -0.026;
  }
  return table;
}

/// VLP-32C: an uneven fan, dense around the horizon (0.33 deg) and sparse
/// towards the ends; beams 4.2 cm off the axis, vertical offsets falling with
/// elevation (-0.5 mm/deg) and scattered by 2 mm.
inline LaserTable vlp32c_table(unsigned seed = 4) {
  const std::vector<double> e = {-25,    -15.639, -11.31, -8.843, -7.254, -6.148, -5.333, -4.667,
                                 -4,     -3.667,  -3.333, -3,     -2.667, -2.333, -2,     -1.667,
                                 -1.333, -1,      -0.667, -0.333, 0,      0.333,  0.667,  1,
                                 1.333,  1.667,   2.333,  3.333,  4.667,  7,      10.333, 15};
  LaserTable table = sweep_detail::build("VLP32C", sweep_detail::degrees_to_radians(e), 0.02, seed);
  std::mt19937 rng(seed + 100);
  std::normal_distribution<double> scatter(0.0, 0.002);
  for (Laser& laser : table.lasers) {
    laser.radial = 0.042;
    laser.vertical_offset = -0.0005 * laser.elevation / sweep_detail::kDeg + scatter(rng);
  }
  return table;
}

/// The model offset h_k of a laser: its returns lie on z = d * tan(e) + h_k
/// (exactly without a lateral offset, within millimetres with one).
inline double model_offset(const Laser& laser) {
  return laser.vertical_offset / std::cos(laser.elevation) -
         laser.radial * std::tan(laser.elevation);
}

/// The point a laser returns at `range` along its beam fired at `azimuth`.
inline Eigen::Vector3d fire(const Laser& laser, double azimuth, double range) {
  const double ce = std::cos(laser.elevation), se = std::sin(laser.elevation);
  const Eigen::Vector3d forward(std::cos(azimuth), std::sin(azimuth), 0.0);
  const Eigen::Vector3d left(-std::sin(azimuth), std::cos(azimuth), 0.0);
  const Eigen::Vector3d direction = ce * forward + se * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d normal = -se * forward + ce * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d origin =
      laser.radial * forward + laser.lateral * left + laser.vertical_offset * normal;
  return origin + range * direction;
}

/// How points are spread over the beams and what corrupts them.
struct SweepOptions {
  int points_per_laser = 400;
  double min_range = 0.2;     ///< [m] ranges are log-uniform in [min, max]
  double max_range = 60.0;    ///< [m]
  double range_sigma = 0.01;  ///< [m] range noise (along the beam)
  double jitter_deg = 0.02;   ///< [deg] elevation noise per return
  std::set<int> silent;       ///< lasers without any return
  int invalid_points = 100;   ///< NaN and (0, 0, 0) "no return" points
  unsigned seed = 17;
};

/// A sweep and the laser of each point (-1 for invalid points).
struct LaserSweep {
  LidarCloud cloud;
  std::vector<int> truth;
};

/// Random azimuths and log-uniform ranges per laser, shuffled (drivers emit
/// firing order, not rings), with NaN and zero points mixed in.
inline LaserSweep laser_sweep(const LaserTable& table, const SweepOptions& options) {
  std::mt19937 rng(options.seed);
  std::uniform_real_distribution<double> azimuth(-M_PI, M_PI);
  std::uniform_real_distribution<double> log_range(std::log(options.min_range),
                                                   std::log(options.max_range));
  std::normal_distribution<double> range_noise(0.0, options.range_sigma);
  std::normal_distribution<double> jitter(0.0, options.jitter_deg * sweep_detail::kDeg);
  LaserSweep sweep;
  for (int k = 0; k < static_cast<int>(table.lasers.size()); ++k) {
    if (options.silent.count(k)) continue;
    for (int i = 0; i < options.points_per_laser; ++i) {
      Laser laser = table.lasers[k];
      laser.elevation += jitter(rng);
      const double range = std::exp(log_range(rng)) + range_noise(rng);
      sweep.cloud.points.push_back(fire(laser, azimuth(rng), range));
      sweep.truth.push_back(k);
    }
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (int i = 0; i < options.invalid_points / 2; ++i) {
    sweep.cloud.points.emplace_back(nan, nan, nan);
    sweep.cloud.points.emplace_back(0.0, 0.0, 0.0);
    sweep.truth.insert(sweep.truth.end(), {-1, -1});
  }
  std::vector<std::size_t> order(sweep.truth.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::shuffle(order.begin(), order.end(), rng);
  LaserSweep shuffled;
  for (std::size_t i : order) {
    shuffled.cloud.points.push_back(sweep.cloud.points[i]);
    shuffled.truth.push_back(sweep.truth[i]);
  }
  return shuffled;
}

/// A corridor as a lidar on a cart sees it: floor `height` below the sensor,
/// ceiling 2.6 m above the floor, walls `half_width` to each side, end walls
/// 25 m ahead and behind, and a post 0.35 m from the sensor (near returns at
/// 0.2-0.5 m). Every laser fires every `azimuth_step_deg`; returns are in
/// firing order (column by column), as organised clouds store them.
struct CorridorOptions {
  double height = 0.9;            ///< [m] sensor above the floor
  double half_width = 1.3;        ///< [m]
  double azimuth_step_deg = 0.4;  ///< [deg]
  double range_sigma = 0.01;      ///< [m]
  double jitter_deg = 0.02;       ///< [deg]
  unsigned seed = 5;
};

/// Range from `origin` along unit `direction` to the first corridor surface.
inline double corridor_range(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                             const CorridorOptions& options) {
  double best = std::numeric_limits<double>::infinity();
  const auto plane = [&](int axis, double value) {
    if (std::abs(direction[axis]) < 1e-12) return;
    const double s = (value - origin[axis]) / direction[axis];
    if (s > 0.0) best = std::min(best, s);
  };
  plane(2, -options.height);
  plane(2, 2.6 - options.height);
  plane(1, options.half_width);
  plane(1, -options.half_width);
  plane(0, 25.0);
  plane(0, -25.0);
  // A post of radius 0.06 m at (0.25, -0.25), from the floor to 1.5 m.
  const Eigen::Vector2d c(0.25, -0.25), o = origin.head<2>() - c, d = direction.head<2>();
  const double a = d.squaredNorm(), b = o.dot(d), q = o.squaredNorm() - 0.06 * 0.06;
  if (a > 1e-12 && b * b - a * q > 0.0) {
    const double s = (-b - std::sqrt(b * b - a * q)) / a;
    const double z = origin.z() + s * direction.z();
    if (s > 0.0 && z > -options.height && z < 1.5 - options.height) best = std::min(best, s);
  }
  return best;
}

/// The corridor sweep, organised: row k holds laser k's returns (missing
/// returns are NaN, as drivers pad organised clouds), `columns` per row.
struct OrganisedSweep {
  LidarCloud cloud;
  std::size_t rows = 0, columns = 0;
};

inline OrganisedSweep corridor_sweep(const LaserTable& table, const CorridorOptions& options) {
  std::mt19937 rng(options.seed);
  std::normal_distribution<double> range_noise(0.0, options.range_sigma);
  std::normal_distribution<double> jitter(0.0, options.jitter_deg * sweep_detail::kDeg);
  OrganisedSweep sweep;
  sweep.rows = table.lasers.size();
  sweep.columns = static_cast<std::size_t>(std::lround(360.0 / options.azimuth_step_deg));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const Laser& nominal : table.lasers)
    for (std::size_t c = 0; c < sweep.columns; ++c) {
      Laser laser = nominal;
      laser.elevation += jitter(rng);
      const double azimuth = -M_PI + c * options.azimuth_step_deg * sweep_detail::kDeg;
      const Eigen::Vector3d origin = fire(laser, azimuth, 0.0);
      const Eigen::Vector3d direction = fire(laser, azimuth, 1.0) - origin;
      const double range = corridor_range(origin, direction, options);
      sweep.cloud.points.push_back(std::isfinite(range)
                                       ? fire(laser, azimuth, range + range_noise(rng))
                                       : Eigen::Vector3d(nan, nan, nan));
    }
  return sweep;
}

/// Number of distinct ring values among the points of `truth` >= 0.
inline std::size_t distinct_rings(const LidarCloud& cloud, const std::vector<int>& truth) {
  std::set<int> rings;
  for (std::size_t i = 0; i < truth.size(); ++i)
    if (truth[i] >= 0) rings.insert(cloud.ring[i]);
  return rings.size();
}

}  // namespace l2s::test
