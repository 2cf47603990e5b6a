#include "sim/beam_footprint.hpp"

#include <l2s/error.hpp>

#include "sim/random.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace l2s::sim::detail {
namespace {

constexpr double kGoldenAngle = 2.39996322972865332;  // [rad] pi * (3 - sqrt 5)

/// One sub-ray's echo before merging.
struct Part {
  double t;          ///< [m]
  double power;      ///< weight * reflectivity * cos / t^2
  double weight;     ///< share of the footprint
  double intensity;  ///< weight * full-footprint intensity
  SurfaceId surface;
};

/// A merged echo: sub-ray echoes within the range resolution of each other.
struct Merged {
  double power = 0.0, weight = 0.0, power_t = 0.0, intensity = 0.0, strongest = 0.0, near = 0.0, far = 0.0;
  SurfaceId surface = SurfaceId::None;
};

}  // namespace

double lidar_reflectivity(SurfaceId surface) {
  // Calibrated reflectivity (0..255): the painted board returns more than the
  // walls, the ground least, the stand is dark metal.
  switch (surface) {
    case SurfaceId::Board: return 180.0;
    case SurfaceId::Wall: return 60.0;
    case SurfaceId::Ground: return 30.0;
    case SurfaceId::Clutter: return 100.0;
    case SurfaceId::Stand: return 40.0;
    case SurfaceId::SideWall: return 70.0;
    case SurfaceId::Pillar: return 90.0;
    case SurfaceId::None: return 0.0;
  }
  return 0.0;
}

float lidar_intensity(SurfaceId surface, double cos_incidence) {
  if (surface == SurfaceId::None) return 0.0f;
  return static_cast<float>(lidar_reflectivity(surface) * (0.3 + 0.7 * std::clamp(cos_incidence, 0.0, 1.0)));
}

Echo ray_echo(const Hit& hit, const Eigen::Vector3d& direction, double min_range, double max_range) {
  Echo echo;
  if (!hit.hit() || hit.t < min_range || hit.t > max_range) return echo;
  echo.range = hit.t;
  echo.intensity = lidar_intensity(hit.surface, std::abs(hit.normal.dot(direction)));
  echo.surface = hit.surface;
  return echo;
}

BeamFootprint::BeamFootprint(const BeamOptics& optics, Params params) : optics_(optics), params_(params) {
  if (params_.rays < 7 || params_.rays > 256) throw ParamError("footprint_rays", "must be 7..256");
  if (!(params_.min_share > 0.0 && params_.min_share < 1.0)) throw ParamError("min_return_share", "must be in (0, 1)");
  if (!(params_.echo_jitter >= 0.0 && params_.echo_jitter <= 2.0)) throw ParamError("echo_jitter", "must be 0..2");
  double total = 0.0;
  for (int i = 0; i < params_.rays; ++i) {
    const double rho = std::sqrt((i + 0.5) / params_.rays);
    const double angle = i * kGoldenAngle;
    const double weight = std::exp(-2.0 * rho * rho);  // Gaussian beam, 1/e^2 at the rim
    rays_.push_back(SubRay{rho * std::cos(angle), rho * std::sin(angle), weight});
    total += weight;
  }
  for (SubRay& ray : rays_) ray.weight /= total;
  cone_.radius0 = 0.5 * optics_.exit_diameter;
  cone_.slope = std::tan(0.5 * std::max(optics_.divergence_horizontal, optics_.divergence_vertical)) * 1.0001;
}

Echo BeamFootprint::fire(const RayCaster& caster, const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                         const Eigen::Vector3d& left, const Eigen::Vector3d& up, double min_range,
                         double max_range, std::uint64_t jitter_bits) const {
  const double spread_h = std::tan(0.5 * optics_.divergence_horizontal);
  const double spread_v = std::tan(0.5 * optics_.divergence_vertical);
  const double r0 = 0.5 * optics_.exit_diameter;
  std::array<Part, 256> parts;
  int n = 0;
  for (const SubRay& ray : rays_) {
    const Eigen::Vector3d o = origin + r0 * (ray.s * left + ray.q * up);
    const Eigen::Vector3d d = (direction + spread_h * ray.s * left + spread_v * ray.q * up).normalized();
    const Hit hit = caster.cast(o, d);
    if (!hit.hit() || hit.t < min_range || hit.t > max_range) continue;
    const double cosine = std::abs(hit.normal.dot(d));
    const double power = ray.weight * lidar_reflectivity(hit.surface) * std::max(cosine, 0.02) / (hit.t * hit.t);
    parts[n++] = Part{hit.t, power, ray.weight, ray.weight * lidar_intensity(hit.surface, cosine), hit.surface};
  }
  if (n == 0) return Echo{};
  std::sort(parts.begin(), parts.begin() + n, [](const Part& a, const Part& b) { return a.t < b.t; });

  // Merge echoes closer than the range resolution, then pick by return mode.
  Echo best;
  double best_key = -1e300;
  int index = 0;
  for (int i = 0; i < n; ++index) {
    Merged m;
    m.near = parts[i].t;
    int j = i;
    for (; j < n && (j == i || parts[j].t - parts[j - 1].t <= optics_.range_resolution); ++j) {
      m.power += parts[j].power;
      m.weight += parts[j].weight;
      m.power_t += parts[j].power * parts[j].t;
      m.intensity += parts[j].intensity;
      if (parts[j].power > m.strongest) m.strongest = parts[j].power, m.surface = parts[j].surface;
    }
    m.far = parts[j - 1].t;
    i = j;
    if (m.weight < params_.min_share) continue;
    const double sigma = params_.echo_jitter;
    const double power =
        m.power * std::exp(sigma * standard_normal(hash_counters(jitter_bits, 0xEC40, index)) - 0.5 * sigma * sigma);
    const double key = params_.mode == ReturnMode::Strongest ? power
                       : params_.mode == ReturnMode::Last    ? m.far
                                                             : -m.near;
    if (key > best_key) {
      best_key = key;
      best.range = m.power_t / m.power;
      best.intensity = static_cast<float>(m.intensity);
      best.surface = m.surface;
    }
  }
  return best;
}

}  // namespace l2s::sim::detail
