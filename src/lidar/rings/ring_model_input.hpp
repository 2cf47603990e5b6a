#pragma once
// The returns of a sweep in the coordinates of the laser model (laser_line.hpp).

#include <l2s/types.hpp>

#include "lidar/rings/laser_line.hpp"

#include <cmath>
#include <vector>

namespace l2s::io {

/// Returns in model coordinates and where each sits in the cloud.
struct ModelInput {
  std::vector<fan::Point> points;
  std::vector<std::size_t> index;  ///< cloud index of points[i]
};

/// The returns that can have a ring: finite, and off the spin axis (a return at
/// the origin is how some drivers write "no return").
inline ModelInput model_input(const LidarCloud& cloud, std::size_t begin = 0,
                              std::size_t end = static_cast<std::size_t>(-1)) {
  constexpr double kMinDistance = 1e-3;  // [m] horizontal
  // Beyond any lidar: farther than 1 km, or steeper than 89.4 deg. Such values
  // are garbage, and they would stretch the models' histograms without bound.
  constexpr double kMaxRange = 1000.0;  // [m]
  constexpr double kMaxSlope = 100.0;   // |z| / horizontal distance
  ModelInput input;
  end = std::min(end, cloud.size());
  input.points.reserve(end > begin ? end - begin : 0);
  input.index.reserve(end > begin ? end - begin : 0);
  for (std::size_t i = begin; i < end; ++i) {
    const Eigen::Vector3d& p = cloud.points[i];
    if (!p.allFinite()) continue;
    const double d = std::sqrt(p.x() * p.x() + p.y() * p.y());
    if (!(d >= kMinDistance) || d > kMaxRange || std::abs(p.z()) > kMaxSlope * d) continue;
    input.points.push_back({1.0 / d, p.z() / d});
    input.index.push_back(i);
  }
  return input;
}

}  // namespace l2s::io
