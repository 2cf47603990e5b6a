#pragma once
// The geometry of one laser firing in the lidar frame: where the beam starts
// and where it points, with the two directions across it (for its footprint).
// A Velodyne driver computes points from exactly this geometry (distance
// along the corrected beam from the laser's own origin), so the points it
// reports are exact up to range noise.

#include <l2s/sim/lidar_model.hpp>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>

namespace l2s::sim::detail {

struct LaserBeam {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  ///< [m] lidar frame
  Eigen::Vector3d direction;                         ///< unit
  Eigen::Vector3d left;                              ///< unit, horizontal, across the beam
  Eigen::Vector3d up;                                ///< unit, across the beam and `left`
};

/// One laser of a spinning head, its angles' sines and cosines computed once
/// per sweep: the beam at encoder angle a follows by angle addition.
struct SpinningLaser {
  double cos_el = 1.0, sin_el = 0.0;    ///< of the (corrected) elevation
  double cos_az = 1.0, sin_az = 0.0;    ///< of the azimuth correction
  double vertical_offset = 0.0;         ///< [m]
  double horizontal_offset = 0.0;       ///< [m]

  SpinningLaser() = default;
  SpinningLaser(const LidarModel& model, int ring) {
    double el = model.elevations[ring], az = 0.0;
    if (!model.corrections.empty()) {
      const LidarModel::LaserCorrection& c = model.corrections[ring];
      el += c.elevation;
      az = c.azimuth;
      vertical_offset = c.vertical_offset;
      horizontal_offset = c.horizontal_offset;
    }
    cos_el = std::cos(el), sin_el = std::sin(el);
    cos_az = std::cos(az), sin_az = std::sin(az);
  }

  /// The beam with the head at the encoder angle whose cosine and sine are ca, sa.
  LaserBeam at(double ca, double sa) const {
    // cos/sin of (encoder angle + correction); exact when the correction is 0.
    const double c = ca * cos_az - sa * sin_az, s = sa * cos_az + ca * sin_az;
    LaserBeam beam;
    beam.direction = Eigen::Vector3d(cos_el * c, cos_el * s, sin_el);
    beam.left = Eigen::Vector3d(-s, c, 0.0);
    beam.up = Eigen::Vector3d(-sin_el * c, -sin_el * s, cos_el);
    if (vertical_offset != 0.0 || horizontal_offset != 0.0)
      beam.origin = vertical_offset * beam.up + horizontal_offset * beam.left;
    return beam;
  }
};

/// A beam at `elevation` and `azimuth` [rad] from the sensor origin.
inline LaserBeam laser_beam(double elevation, double azimuth) {
  SpinningLaser laser;
  laser.cos_el = std::cos(elevation), laser.sin_el = std::sin(elevation);
  return laser.at(std::cos(azimuth), std::sin(azimuth));
}

/// Laser `ring` of a spinning model with the head at encoder angle `azimuth`,
/// with the unit's corrections when the model has them.
inline LaserBeam spinning_beam(const LidarModel& model, int ring, double azimuth) {
  return SpinningLaser(model, ring).at(std::cos(azimuth), std::sin(azimuth));
}

/// The elevation [rad] under which laser `ring` is seen from the sensor origin
/// at horizontal distance `distance` [m] (differs from the beam's own
/// elevation when the laser starts off the origin).
inline double apparent_elevation(const LidarModel& model, int ring, double distance) {
  if (model.corrections.empty()) return model.elevations[ring];
  const LidarModel::LaserCorrection& c = model.corrections[ring];
  const double el = model.elevations[ring] + c.elevation;
  return el + std::atan2(c.vertical_offset, std::max(distance, 1e-3));
}

}  // namespace l2s::sim::detail
