// The lidar side of the placement check. Spinning lidars (paper, Sec. III-C):
// for every hole at least two rings whose rays pass through the hole onto the
// wall for any azimuth offset of the sweep, with board returns on both sides
// (the depth discontinuities the hole detector looks for). Ring-free lidars:
// enough returns through each hole and on the board around its rim within the
// accumulation time, so the holes stand out in the accumulated board points.

#include "sim/placement_lidar.hpp"

#include "sim/laser_beam.hpp"
#include "sim/rosette_scan.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <vector>

namespace l2s::sim::detail {

const char* const kHoleNames[4] = {"TopLeft", "TopRight", "BottomLeft", "BottomRight"};

namespace {

/// Samples per azimuth step when measuring a ring's path across a hole.
constexpr int kFine = 4;

/// [m] how far behind the board plane another surface must be to count as
/// the background of a hole (a depth step the detector sees).
constexpr double kBackgroundDepth = 0.3;

/// Range along the ray to the board's front plane (infinite when parallel or behind).
double board_plane_range(const Scene& scene, const Eigen::Vector3d& origin, const Eigen::Vector3d& dir) {
  const Eigen::Vector3d normal = scene.T_cambody_board.linear().col(2);
  const double along = normal.dot(dir);
  if (std::abs(along) < 1e-12) return 1e30;
  const double t = normal.dot(scene.T_cambody_board.translation() - origin) / along;
  return t > 0.0 ? t : 1e30;
}

/// 0 other, 1 board, 2 through `hole` onto the wall (or a side wall or pillar
/// well behind), 3 through onto something else, 4 an object in front of the board.
int classify(const RayCaster& caster, const LidarModel& lidar, const Eigen::Vector3d& origin,
             const Eigen::Vector3d& dir, int hole) {
  const Hit hit = caster.cast(origin, dir);
  if (hit.surface == SurfaceId::Board)
    return hit.t >= lidar.min_range && hit.t <= lidar.max_range ? 1 : 0;
  const bool obstacle = hit.surface == SurfaceId::Clutter || hit.surface == SurfaceId::Stand ||
                        hit.surface == SurfaceId::Pillar || hit.surface == SurfaceId::SideWall;
  const double t_plane = obstacle ? board_plane_range(caster.scene(), origin, dir) : 0.0;
  if (obstacle && hit.t < t_plane - 0.05) return 4;
  if (caster.hole_on_front_plane(origin, dir) != hole) return 0;
  const bool far_behind = (hit.surface == SurfaceId::SideWall || hit.surface == SurfaceId::Pillar) &&
                          hit.t > t_plane + kBackgroundDepth;
  return (hit.surface == SurfaceId::Wall || far_behind) && hit.t <= lidar.max_range ? 2 : 3;
}

/// [rad] how far the encoder angle lags the azimuth at which laser `ring`
/// reaches a point `distance` away: its azimuth correction plus the parallax
/// of its sideways offset.
double encoder_lag(const LidarModel& lidar, int ring, double distance) {
  if (lidar.corrections.empty()) return 0.0;
  const LidarModel::LaserCorrection& c = lidar.corrections[ring];
  return c.azimuth - std::atan2(c.horizontal_offset, std::max(distance, 1e-3));
}

/// How ring `ring` crosses hole `hole`, for the worst azimuth offset.
RingCrossing cross_ring(const RayCaster& caster, const LidarModel& lidar,
                        const Eigen::Isometry3d& T_cambody_lidar, int hole, int ring,
                        double azimuth_center, double half_window) {
  RingCrossing crossing;
  crossing.hole = hole;
  crossing.ring = ring;
  const double fine = lidar.azimuth_step / kFine;
  const int n = static_cast<int>(std::ceil(half_window / fine));
  // 0 other, 1 board, 2 through onto the wall, 3 through onto something else,
  // 4 an object in front of the board.
  std::vector<int> cls(static_cast<std::size_t>(2 * n + 1));
  for (int i = -n; i <= n; ++i) {
    const LaserBeam beam = spinning_beam(lidar, ring, azimuth_center + i * fine);
    const Eigen::Vector3d origin =
        beam.origin.isZero(0.0) ? Eigen::Vector3d(T_cambody_lidar.translation()) : T_cambody_lidar * beam.origin;
    const Eigen::Vector3d dir = T_cambody_lidar.linear() * beam.direction;
    cls[static_cast<std::size_t>(i + n)] = classify(caster, lidar, origin, dir, hole);
  }
  crossing.occluded = std::count(cls.begin(), cls.end(), 4) > 0;
  const auto through = [](int c) { return c == 2 || c == 3; };
  // The longest run of samples through the hole.
  int best_begin = -1, best_len = 0;
  for (int i = 0; i < static_cast<int>(cls.size());) {
    if (!through(cls[i])) {
      ++i;
      continue;
    }
    int j = i;
    while (j < static_cast<int>(cls.size()) && through(cls[j])) ++j;
    if (j - i > best_len) {
      best_len = j - i;
      best_begin = i;
    }
    i = j;
  }
  if (best_len == 0) return crossing;
  // n samples span at least (n - 1) fine steps, so any offset puts at least
  // floor((n - 1) / kFine) firings inside.
  crossing.rays_through = (best_len - 1) / kFine;
  for (int i = best_begin; i < best_begin + best_len; ++i)
    if (cls[i] == 3) crossing.background_is_wall = false;
  const auto board_run = [&](int start, int step) {
    int count = 0;
    for (int i = start; i >= 0 && i < static_cast<int>(cls.size()) && cls[i] == 1; i += step) ++count;
    return count;
  };
  const int left = board_run(best_begin - 1, -1);
  const int right = board_run(best_begin + best_len, +1);
  crossing.board_both_sides = left > kFine && right > kFine;
  return crossing;
}

}  // namespace

void check_lidar_rings(const RayCaster& caster, const LidarModel& lidar, const Eigen::Isometry3d& T_cambody_lidar,
                       const PlacementRequirements& req, PlacementReport* report) {
  const Scene& scene = caster.scene();
  const Eigen::Isometry3d T_lidar_cambody = T_cambody_lidar.inverse();
  const auto holes = scene.target.hole_centers();
  int second_min = 1 << 30;
  for (int hole = 0; hole < 4; ++hole) {
    const Eigen::Vector3d c = T_lidar_cambody * (scene.T_cambody_board *
                                                 Eigen::Vector3d(holes[hole].x(), holes[hole].y(), 0.0));
    const double range = c.norm();
    const double azimuth = std::atan2(c.y(), c.x());
    const double elevation = std::atan2(c.z(), std::hypot(c.x(), c.y()));
    const double radius = std::asin(std::min(1.0, (scene.target.hole_radius + 0.02) / range));
    // Wide enough for the hole plus board on each side at any incidence.
    const double half_window = radius / std::max(0.2, std::cos(elevation)) + 3.0 * lidar.azimuth_step;
    const double distance = std::hypot(c.x(), c.y());
    std::vector<int> rays;
    for (int ring = 0; ring < lidar.rings(); ++ring) {
      if (std::abs(apparent_elevation(lidar, ring, distance) - elevation) > radius) continue;
      const RingCrossing crossing = cross_ring(caster, lidar, T_cambody_lidar, hole, ring,
                                               azimuth - encoder_lag(lidar, ring, distance), half_window);
      if (crossing.rays_through == 0 && !crossing.occluded) continue;
      report->crossings.push_back(crossing);
      if (crossing.counts()) {
        ++report->rings_per_hole[hole];
        rays.push_back(crossing.rays_through);
      }
    }
    std::sort(rays.rbegin(), rays.rend());
    second_min = std::min(second_min, rays.size() >= 2 ? rays[1] : 0);
    if (report->rings_per_hole[hole] < req.min_rings_per_hole) {
      std::ostringstream s;
      s << lidar.name << ": hole " << kHoleNames[hole] << " crossed by " << report->rings_per_hole[hole]
        << " ring(s), need " << req.min_rings_per_hole << " (rings near it:";
      int listed = 0;
      for (const RingCrossing& rc : report->crossings) {
        if (rc.hole != hole) continue;
        s << " " << rc.ring << ":" << rc.rays_through << " rays" << (rc.board_both_sides ? "" : " no board both sides")
          << (rc.background_is_wall ? "" : " background not the wall") << (rc.occluded ? " occluded" : "");
        ++listed;
      }
      if (listed == 0) s << " none";
      s << ")";
      report->failures.push_back(s.str());
    }
  }
  report->min_rays_second_ring = second_min;
}

namespace {

/// The board's extent as seen from the lidar: azimuths (relative to its
/// centre's) and elevations of its corners, widened by `margin` [rad].
struct AngularBox {
  double azimuth_center = 0.0, azimuth_lo = 0.0, azimuth_hi = 0.0, elevation_lo = 0.0, elevation_hi = 0.0;
  bool contains(double azimuth, double elevation) const {
    const double a = std::remainder(azimuth - azimuth_center, 2.0 * M_PI);
    return a >= azimuth_lo && a <= azimuth_hi && elevation >= elevation_lo && elevation <= elevation_hi;
  }
};

AngularBox board_box(const Scene& scene, const Eigen::Isometry3d& T_lidar_cambody, double margin) {
  const Target& t = scene.target;
  const Eigen::Vector3d center = T_lidar_cambody * scene.T_cambody_board.translation();
  AngularBox box;
  box.azimuth_center = std::atan2(center.y(), center.x());
  box.azimuth_lo = box.elevation_lo = 1e9;
  box.azimuth_hi = box.elevation_hi = -1e9;
  for (double sx : {-0.5, 0.5})
    for (double sy : {-0.5, 0.5}) {
      const Eigen::Vector3d p = T_lidar_cambody * (scene.T_cambody_board * Eigen::Vector3d(sx * t.board_width, sy * t.board_height, 0.0));
      const double a = std::remainder(std::atan2(p.y(), p.x()) - box.azimuth_center, 2.0 * M_PI);
      const double e = std::atan2(p.z(), std::hypot(p.x(), p.y()));
      box.azimuth_lo = std::min(box.azimuth_lo, a - margin), box.azimuth_hi = std::max(box.azimuth_hi, a + margin);
      box.elevation_lo = std::min(box.elevation_lo, e - margin), box.elevation_hi = std::max(box.elevation_hi, e + margin);
    }
  return box;
}

}  // namespace

void check_lidar_rosette(const RayCaster& caster, const LidarModel& lidar, const Eigen::Isometry3d& T_cambody_lidar,
                         const PlacementRequirements& req, PlacementReport* report) {
  report->ring_free = true;
  const Scene& scene = caster.scene();
  const Target& target = scene.target;
  const Eigen::Isometry3d T_board_cambody = scene.T_cambody_board.inverse();
  const AngularBox box = board_box(scene, T_cambody_lidar.inverse(), 0.02);
  // Every firing of the accumulation time; only those towards the board are cast.
  const int count = static_cast<int>(std::lround(req.accumulation_time * lidar.rosette.point_rate));
  std::vector<double> azimuth, elevation;
  rosette_angles(lidar.rosette, 0, count, &azimuth, &elevation);
  const Eigen::Vector3d origin = T_cambody_lidar.translation();
  const auto holes = target.hole_centers();
  const double r = target.hole_radius;
  std::array<int, 4>& through = report->returns_through_hole;
  std::array<int, 4>& around = report->returns_around_hole;
  constexpr int kRimSectors = 12;
  std::array<std::array<bool, kRimSectors>, 4> rim_sector_seen{};
  for (int i = 0; i < count; ++i) {
    if (!box.contains(azimuth[i], elevation[i])) continue;
    const Eigen::Vector3d dir = T_cambody_lidar.linear() * laser_beam(elevation[i], azimuth[i]).direction;
    const Eigen::Vector3d o = T_board_cambody * origin;
    const Eigen::Vector3d d = T_board_cambody.linear() * dir;
    if (!(std::abs(d.z()) > 1e-9)) continue;
    const double t_plane = -o.z() / d.z();
    if (t_plane <= 0.0) continue;
    const Eigen::Vector2d q = (o + t_plane * d).head<2>();
    const Hit hit = caster.cast(origin, dir);
    const bool in_range = hit.hit() && hit.t >= lidar.min_range && hit.t <= lidar.max_range;
    for (int h = 0; h < 4; ++h) {
      const double dist = (q - holes[h]).norm();
      if (dist < r && in_range && hit.surface != SurfaceId::Board && hit.t > t_plane + kBackgroundDepth) ++through[h];
      if (dist >= r && dist < r + 0.04 && in_range && hit.surface == SurfaceId::Board &&
          std::abs(hit.t - t_plane) < 0.03) {
        ++around[h];
        const Eigen::Vector2d d = q - holes[h];
        const double turn = (std::atan2(d.y(), d.x()) + M_PI) / (2.0 * M_PI);
        rim_sector_seen[h][std::min(kRimSectors - 1, static_cast<int>(turn * kRimSectors))] = true;
      }
    }
  }
  for (int h = 0; h < 4; ++h) {
    const auto seen = std::count(rim_sector_seen[h].begin(), rim_sector_seen[h].end(), true);
    report->rim_in_view[h] = static_cast<double>(seen) / kRimSectors;
    if (report->rim_in_view[h] + 1e-9 < req.min_rim_in_view) {
      std::ostringstream s;
      s << lidar.name << ": hole " << kHoleNames[h] << " has board returns around only " << seen << " of "
        << kRimSectors << " twelfths of its rim (need " << req.min_rim_in_view * kRimSectors
        << "): the field of view's edge or something in front cuts it";
      report->failures.push_back(s.str());
    }
    if (through[h] >= req.min_returns_through_hole && around[h] >= req.min_returns_around_hole) continue;
    std::ostringstream s;
    s << lidar.name << ": hole " << kHoleNames[h] << " has " << through[h] << " returns through it and "
      << around[h] << " around its rim in " << req.accumulation_time << " s (need " << req.min_returns_through_hole
      << " and " << req.min_returns_around_hole << ")";
    if (through[h] + around[h] == 0) s << ": outside the field of view or range";
    report->failures.push_back(s.str());
  }
}

}  // namespace l2s::sim::detail
