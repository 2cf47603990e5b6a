// One sweep of a lidar: every firing of the scan pattern casts its beam; the
// measured range is the exact echo range plus Gaussian noise along the beam
// (paper, Sec. IV-B: sigma = K * 0.008 m for the Velodyne models). The point
// is reported from the laser's own origin along its corrected direction, as a
// driver does with its calibration table. With the beam footprint on, firings
// whose cone comes near an outline (board border, hole rim, box edge) sample
// the whole footprint (beam_footprint.hpp); all others keep the single ray,
// which gives the same echo there and keeps a sweep fast.

#include <l2s/sim/lidar_simulator.hpp>

#include <l2s/error.hpp>

#include "sim/beam_footprint.hpp"
#include "sim/laser_beam.hpp"
#include "sim/parallel.hpp"
#include "sim/random.hpp"
#include "sim/rosette_scan.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace l2s::sim {
namespace {

// Salts that keep the offset, noise and speckle streams of one seed independent.
constexpr std::uint64_t kOffsetStream = 0x0FF5E7ULL;
constexpr std::uint64_t kRangeStream = 0x4A46E5ULL;
constexpr std::uint64_t kRosetteRangeStream = 0x405E77ULL;
constexpr std::uint64_t kJitterStream = 0x5BEC1EULL;

constexpr double kTwoPi = 6.283185307179586476925;

}  // namespace

struct LidarSimulator::Slot {
  Eigen::Vector3d point;
  float intensity = 0.0f;
  SurfaceId surface = SurfaceId::None;
  bool valid = false;
};

struct LidarSimulator::Beam {
  detail::LaserBeam lidar;       ///< lidar frame
  std::uint64_t jitter_bits = 0;  ///< speckle of this firing
};

LidarSimulator::LidarSimulator(LidarModel model) : LidarSimulator(std::move(model), Params{}) {}

LidarSimulator::LidarSimulator(LidarModel model, Params params)
    : model_(std::move(model)), params_(params) {
  model_.validate();
  if (!(params_.noise_factor >= 0.0)) throw ParamError("noise_factor", "must be >= 0");
  if (params_.beam_footprint) {
    detail::BeamFootprint::Params fp;
    fp.rays = params_.footprint_rays;
    fp.min_share = params_.min_return_share;
    fp.echo_jitter = params_.echo_jitter;
    fp.mode = params_.return_mode;
    footprint_ = std::make_unique<detail::BeamFootprint>(model_.optics, fp);
  }
}

LidarSimulator::~LidarSimulator() = default;
LidarSimulator::LidarSimulator(LidarSimulator&&) noexcept = default;
LidarSimulator& LidarSimulator::operator=(LidarSimulator&&) noexcept = default;

int LidarSimulator::firings_per_sweep() const {
  return model_.has_rings() ? model_.azimuth_count() * model_.rings() : model_.rosette.shots_per_frame();
}

std::vector<Eigen::Vector3d> LidarSimulator::firing_directions(std::uint64_t frame) const {
  std::vector<Eigen::Vector3d> directions;
  if (model_.has_rings()) {
    const double step = kTwoPi / model_.azimuth_count();
    const double offset = azimuth_offset(frame);
    std::vector<detail::SpinningLaser> lasers;
    for (int r = 0; r < model_.rings(); ++r) lasers.emplace_back(model_, r);
    for (int a = 0; a < model_.azimuth_count(); ++a) {
      const double azimuth = offset + a * step;
      for (const detail::SpinningLaser& laser : lasers)
        directions.push_back(laser.at(std::cos(azimuth), std::sin(azimuth)).direction);
    }
    return directions;
  }
  const int count = model_.rosette.shots_per_frame();
  std::vector<double> azimuth, elevation;
  detail::rosette_angles(model_.rosette, frame * static_cast<std::uint64_t>(count), count, &azimuth, &elevation);
  for (int i = 0; i < count; ++i) directions.push_back(detail::laser_beam(elevation[i], azimuth[i]).direction);
  return directions;
}

double LidarSimulator::azimuth_offset(std::uint64_t frame) const {
  if (!params_.random_azimuth_offset || !model_.has_rings()) return 0.0;
  return model_.azimuth_step * detail::uniform01(detail::hash_counters(params_.seed, kOffsetStream, frame));
}

float LidarSimulator::intensity(SurfaceId surface, double cos_incidence) {
  return detail::lidar_intensity(surface, cos_incidence);
}

void LidarSimulator::fire(const RayCaster& caster, const Eigen::Isometry3d& T_cambody_lidar, const Beam& beam,
                          std::uint64_t noise_bits, Slot* slot) const {
  const Eigen::Matrix3d& R = T_cambody_lidar.linear();
  const Eigen::Vector3d origin =
      beam.lidar.origin.isZero(0.0) ? Eigen::Vector3d(T_cambody_lidar.translation()) : T_cambody_lidar * beam.lidar.origin;
  const Eigen::Vector3d dir = R * beam.lidar.direction;
  const Hit hit = caster.cast(origin, dir);
  detail::Echo echo;
  if (footprint_ && caster.near_outline(origin, dir, footprint_->cone(), hit.hit() ? hit.t : model_.max_range))
    echo = footprint_->fire(caster, origin, dir, R * beam.lidar.left, R * beam.lidar.up, model_.min_range,
                            model_.max_range, beam.jitter_bits);
  else
    echo = detail::ray_echo(hit, dir, model_.min_range, model_.max_range);
  if (echo.surface == SurfaceId::None) return;
  const double sigma = params_.noise_factor * model_.range_sigma0;
  const double noise = sigma > 0.0 ? sigma * detail::standard_normal(noise_bits) : 0.0;
  slot->point = beam.lidar.origin + beam.lidar.direction * (echo.range + noise);
  slot->intensity = echo.intensity;
  slot->surface = echo.surface;
  slot->valid = true;
}

std::vector<LidarSimulator::Slot> LidarSimulator::spinning_slots(const RayCaster& caster,
                                                                 const Eigen::Isometry3d& T_cambody_lidar,
                                                                 std::uint64_t frame) const {
  const int rings = model_.rings();
  const int steps = model_.azimuth_count();
  const double offset = azimuth_offset(frame);
  // Firings sit on a whole number of steps per turn, so a sweep never overlaps itself.
  const double step = kTwoPi / steps;
  std::vector<detail::SpinningLaser> lasers;
  for (int r = 0; r < rings; ++r) lasers.emplace_back(model_, r);

  // Each firing fills its own slot; slots are joined in order afterwards, so
  // the output does not depend on the thread count.
  std::vector<Slot> slots(static_cast<std::size_t>(steps) * rings);
  detail::parallel_for(steps, params_.threads, [&](int a) {
    const double azimuth = offset + a * step;
    const double ca = std::cos(azimuth), sa = std::sin(azimuth);
    for (int r = 0; r < rings; ++r) {
      Beam beam;
      beam.lidar = lasers[r].at(ca, sa);
      if (footprint_) beam.jitter_bits = detail::hash_counters(params_.seed, kJitterStream, frame, a, r);
      fire(caster, T_cambody_lidar, beam, detail::hash_counters(params_.seed, kRangeStream, frame, a, r),
           &slots[static_cast<std::size_t>(a) * rings + r]);
    }
  }, 64);
  return slots;
}

std::vector<LidarSimulator::Slot> LidarSimulator::rosette_slots(const RayCaster& caster,
                                                                const Eigen::Isometry3d& T_cambody_lidar,
                                                                std::uint64_t frame) const {
  const int count = model_.rosette.shots_per_frame();
  std::vector<double> azimuth, elevation;
  detail::rosette_angles(model_.rosette, frame * static_cast<std::uint64_t>(count), count, &azimuth, &elevation);
  std::vector<Slot> slots(static_cast<std::size_t>(count));
  detail::parallel_for(count, params_.threads, [&](int i) {
    Beam beam;
    beam.lidar = detail::laser_beam(elevation[i], azimuth[i]);
    if (footprint_) beam.jitter_bits = detail::hash_counters(params_.seed, kJitterStream, frame, i, 0x405E77ULL);
    fire(caster, T_cambody_lidar, beam, detail::hash_counters(params_.seed, kRosetteRangeStream, frame, i),
         &slots[static_cast<std::size_t>(i)]);
  }, 512);
  return slots;
}

LidarCloud LidarSimulator::sweep(const RayCaster& caster, const Eigen::Isometry3d& T_cambody_lidar,
                                 std::uint64_t frame, std::vector<SurfaceId>* surfaces) const {
  const bool spinning = model_.has_rings();
  const std::vector<Slot> slots = spinning ? spinning_slots(caster, T_cambody_lidar, frame)
                                           : rosette_slots(caster, T_cambody_lidar, frame);
  const std::size_t rings = spinning ? static_cast<std::size_t>(model_.rings()) : 1;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  LidarCloud cloud;
  if (surfaces) surfaces->clear();
  for (std::size_t i = 0; i < slots.size(); ++i) {
    if (!slots[i].valid && !params_.nan_for_no_return) continue;
    cloud.points.push_back(slots[i].valid ? slots[i].point : Eigen::Vector3d(nan, nan, nan));
    cloud.intensity.push_back(slots[i].intensity);
    if (spinning) cloud.ring.push_back(static_cast<std::uint16_t>(i % rings));
    if (surfaces) surfaces->push_back(slots[i].surface);
  }
  return cloud;
}

}  // namespace l2s::sim
