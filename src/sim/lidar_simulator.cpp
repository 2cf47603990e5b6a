// One sweep of a spinning lidar: every laser of the beam table fires at each
// azimuth step; the measured range is the exact first hit plus Gaussian noise
// along the ray (paper, Sec. IV-B: sigma = K * 0.008 m).

#include <l2s/sim/lidar_simulator.hpp>

#include <l2s/error.hpp>

#include "sim/parallel.hpp"
#include "sim/random.hpp"

#include <algorithm>
#include <cmath>

namespace l2s::sim {
namespace {

// Salts that keep the offset and the noise streams of one seed independent.
constexpr std::uint64_t kOffsetStream = 0x0FF5E7ULL;
constexpr std::uint64_t kRangeStream = 0x4A46E5ULL;

}  // namespace

LidarSimulator::LidarSimulator(LidarModel model) : LidarSimulator(std::move(model), Params{}) {}

LidarSimulator::LidarSimulator(LidarModel model, Params params)
    : model_(std::move(model)), params_(params) {
  model_.validate();
  if (!(params_.noise_factor >= 0.0)) throw ParamError("noise_factor", "must be >= 0");
}

double LidarSimulator::azimuth_offset(std::uint64_t frame) const {
  if (!params_.random_azimuth_offset) return 0.0;
  return model_.azimuth_step * detail::uniform01(detail::hash_counters(params_.seed, kOffsetStream, frame));
}

float LidarSimulator::intensity(SurfaceId surface, double cos_incidence) {
  // Reflectivity per material (0..255 like Velodyne's calibrated intensity):
  // the painted board returns more than the wall, the ground least.
  double reflectivity = 0.0;
  switch (surface) {
    case SurfaceId::Board: reflectivity = 180.0; break;
    case SurfaceId::Wall: reflectivity = 60.0; break;
    case SurfaceId::Ground: reflectivity = 30.0; break;
    case SurfaceId::Clutter: reflectivity = 100.0; break;
    case SurfaceId::None: return 0.0f;
  }
  return static_cast<float>(reflectivity * (0.3 + 0.7 * std::clamp(cos_incidence, 0.0, 1.0)));
}

LidarCloud LidarSimulator::sweep(const RayCaster& caster, const Eigen::Isometry3d& T_cambody_lidar,
                                 std::uint64_t frame, std::vector<SurfaceId>* surfaces) const {
  const int rings = model_.rings();
  const int steps = model_.azimuth_count();
  const double offset = azimuth_offset(frame);
  // Firings sit on a whole number of steps per turn, so a sweep never overlaps itself.
  const double step = 2.0 * 3.14159265358979323846 / steps;
  const double sigma = params_.noise_factor * model_.range_sigma0;
  const Eigen::Vector3d origin = T_cambody_lidar.translation();
  const Eigen::Matrix3d R = T_cambody_lidar.linear();

  std::vector<double> cos_el(rings), sin_el(rings);
  for (int r = 0; r < rings; ++r) {
    cos_el[r] = std::cos(model_.elevations[r]);
    sin_el[r] = std::sin(model_.elevations[r]);
  }

  // Each azimuth step fills its own slot; slots are joined in order afterwards,
  // so the output does not depend on the thread count.
  struct Slot {
    Eigen::Vector3d point;
    float intensity;
    SurfaceId surface;
    bool valid = false;
  };
  std::vector<Slot> slots(static_cast<std::size_t>(steps) * rings);
  detail::parallel_for(steps, params_.threads, [&](int a) {
    const double azimuth = offset + a * step;
    const double ca = std::cos(azimuth), sa = std::sin(azimuth);
    for (int r = 0; r < rings; ++r) {
      const Eigen::Vector3d dir_lidar(cos_el[r] * ca, cos_el[r] * sa, sin_el[r]);
      const Eigen::Vector3d dir = R * dir_lidar;
      const Hit hit = caster.cast(origin, dir);
      if (!hit.hit() || hit.t < model_.min_range || hit.t > model_.max_range) continue;
      const double noise =
          sigma > 0.0 ? sigma * detail::standard_normal(
                                    detail::hash_counters(params_.seed, kRangeStream, frame, a, r))
                      : 0.0;
      Slot& slot = slots[static_cast<std::size_t>(a) * rings + r];
      slot.point = dir_lidar * (hit.t + noise);
      slot.intensity = intensity(hit.surface, std::abs(hit.normal.dot(dir)));
      slot.surface = hit.surface;
      slot.valid = true;
    }
  }, 64);

  LidarCloud cloud;
  if (surfaces) surfaces->clear();
  for (std::size_t i = 0; i < slots.size(); ++i) {
    if (!slots[i].valid) continue;
    cloud.points.push_back(slots[i].point);
    cloud.intensity.push_back(slots[i].intensity);
    cloud.ring.push_back(static_cast<std::uint16_t>(i % static_cast<std::size_t>(rings)));
    if (surfaces) surfaces->push_back(slots[i].surface);
  }
  return cloud;
}

}  // namespace l2s::sim
