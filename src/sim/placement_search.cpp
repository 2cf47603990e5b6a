// Deterministic search for a board pose that passes check_placement for every
// lidar model, keeping the one with the most margin (rays through the
// second-best ring of the worst hole, rings per hole, image margin,
// verticality). Ray-cast checks cost about a millisecond, so every grid pose
// is first rated by a closed-form estimate of the same margins; the exact
// check then runs on the best-rated poses, batch by batch, until some pass.

#include <l2s/sim/placement.hpp>

#include <l2s/error.hpp>

#include "sim/laser_beam.hpp"
#include "sim/parallel.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace l2s::sim {
namespace {

constexpr int kBatch = 24;

struct Margins {
  int second_rays = 0;     ///< rays of the 2nd-best ring, worst hole and model
  int rings = 0;           ///< rings per hole, worst hole and model
  double image = 0.0;      ///< [px]
  double elevation = 0.0;  ///< [rad] largest normal elevation
};

double score(const Margins& m, const PlacementRequirements& req) {
  return std::min(m.second_rays, 20) / 20.0 +
         0.25 * std::clamp(m.rings - req.min_rings_per_hole, -4, 2) +
         std::min(m.image, 150.0) / 150.0 +
         0.5 * (req.max_normal_elevation - m.elevation) / req.max_normal_elevation;
}

/// A ring-free lidar's margins in the units of a ring lidar's: enough
/// returns count as two spare rings, too few as one ring short; the rays of
/// the second ring grow with the returns through the hole.
void add_rosette_margins(int through, int around, const PlacementRequirements& req, Margins* m) {
  const bool enough = through >= req.min_returns_through_hole && around >= req.min_returns_around_hole;
  m->rings = std::min(m->rings, req.min_rings_per_hole + (enough ? 2 : -1));
  m->second_rays = std::min(m->second_rays, std::min(20, 20 * through / std::max(1, 4 * req.min_returns_through_hole)));
}

struct RosetteExpectation {
  int through = 0;  ///< returns through the hole in the accumulation time
  int around = 0;   ///< returns in the 4 cm ring around its rim
};

/// Expected returns through and around a hole centred at `c` (lidar frame) of
/// angular radius `alpha`: the firings of the accumulation time times the
/// share of the field of view the hole covers (the rosette's density taken
/// as even), zero outside the field of view or the range.
RosetteExpectation expect_rosette(const LidarModel& lidar, const Eigen::Vector3d& c, double facing, double alpha,
                                  double hole_radius, const PlacementRequirements& req) {
  const RosetteScan& r = lidar.rosette;
  const double range = c.norm();
  const double azimuth = std::atan2(c.y(), c.x());
  const double elevation = std::atan2(c.z(), std::hypot(c.x(), c.y()));
  const bool turning = r.rotation_rate > 0.0;
  // The hole's disc reaches alpha farther out in azimuth and in elevation.
  const double middle = 0.5 * (r.elevation_max + r.elevation_min);
  const double far_elevation = middle + std::abs(elevation - middle) + alpha;
  const bool in_view = r.field_of_view_position(std::abs(azimuth) + alpha, far_elevation) < 1.0 &&
                       range > lidar.min_range && range < lidar.max_range;
  if (!in_view) return {};
  const double span = r.elevation_max - r.elevation_min;
  const double fov = turning ? 2.0 * M_PI * span : M_PI * r.azimuth_half_width * 0.5 * span;  // [rad^2]
  const double firings = req.accumulation_time * r.point_rate;
  const double hole = M_PI * alpha * alpha * facing;
  const double rim = facing * M_PI * (std::pow(alpha * (1.0 + 0.04 / hole_radius), 2) - alpha * alpha);
  return {static_cast<int>(firings * hole / fov), static_cast<int>(firings * rim / fov)};
}

/// Closed-form margins: projected corners, hole discs as seen from the lidar
/// (rings within the hole's angular radius, chord length per ring; expected
/// returns for a ring-free lidar). No ray casting.
Margins estimate(const Target& target, const BoardPose& pose, const SensorSetting& setting,
                 const std::vector<LidarModel>& lidars, const StereoRig& rig, const PlacementRequirements& req) {
  Margins m;
  const Eigen::Isometry3d T_cambody_board = pose.T_cambody_board();
  m.image = 1e9;
  for (int camera = 0; camera < 2; ++camera) {
    const Eigen::Isometry3d T = rig.T_cambody_optical(camera).inverse() * T_cambody_board;
    for (double sx : {-0.5, 0.5})
      for (double sy : {-0.5, 0.5})
        for (double z : {0.0, -target.board_thickness}) {
          const Eigen::Vector3d p = T * Eigen::Vector3d(sx * target.board_width, sy * target.board_height, z);
          const Eigen::Vector2d px = rig.project_optical(camera, p);
          if (p.z() < 0.1 || !px.allFinite()) return Margins{0, 0, -1e9, 10.0};
          const double u = px.x(), v = px.y();
          m.image = std::min({m.image, u + 0.5, rig.width - 0.5 - u, v + 0.5, rig.height - 0.5 - v});
        }
  }
  const Eigen::Isometry3d T_lidar_board = setting.T_cambody_lidar().inverse() * T_cambody_board;
  const Eigen::Vector3d normal_body = T_cambody_board.linear().col(2);
  const Eigen::Vector3d normal_lidar = T_lidar_board.linear().col(2);
  m.elevation = std::max(std::asin(std::min(1.0, std::abs(normal_body.z()))),
                         std::asin(std::min(1.0, std::abs(normal_lidar.z()))));
  m.second_rays = 1 << 30;
  m.rings = 1 << 30;
  for (const Eigen::Vector2d& hole : target.hole_centers()) {
    const Eigen::Vector3d c = T_lidar_board * Eigen::Vector3d(hole.x(), hole.y(), 0.0);
    const Eigen::Vector3d view = c.normalized();
    // Foreshortening of the hole across the line of sight.
    const double facing = std::abs(normal_lidar.dot(view));
    const double alpha = std::asin(std::min(1.0, target.hole_radius / c.norm()));
    const double elevation = std::atan2(c.z(), std::hypot(c.x(), c.y()));
    for (const LidarModel& lidar : lidars) {
      if (!lidar.has_rings()) {
        const RosetteExpectation e = expect_rosette(lidar, c, facing, alpha, target.hole_radius, req);
        add_rosette_margins(e.through, e.around, req, &m);
        continue;
      }
      std::vector<int> rays;
      for (int ring = 0; ring < lidar.rings(); ++ring) {
        const double el = detail::apparent_elevation(lidar, ring, std::hypot(c.x(), c.y()));
        const double d = std::abs(el - elevation);
        if (d >= alpha) continue;
        const double chord = 2.0 * std::sqrt(alpha * alpha - d * d) * facing / std::cos(elevation);
        rays.push_back(static_cast<int>(chord / lidar.azimuth_step) - 1);
      }
      std::sort(rays.rbegin(), rays.rend());
      const int good = static_cast<int>(std::count_if(rays.begin(), rays.end(), [](int r) { return r >= 2; }));
      m.rings = std::min(m.rings, good);
      m.second_rays = std::min(m.second_rays, rays.size() >= 2 ? rays[1] : 0);
    }
  }
  return m;
}

/// estimate() for the lidars at `setting` and each of `also` at its own.
Margins estimate_all(const Target& target, const BoardPose& pose, const SensorSetting& setting,
                     const std::vector<LidarModel>& lidars, const std::vector<MountedLidar>& also,
                     const StereoRig& rig, const PlacementRequirements& req) {
  Margins m = estimate(target, pose, setting, lidars, rig, req);
  for (const MountedLidar& extra : also) {
    const Margins e = estimate(target, pose, extra.setting, {extra.model}, rig, req);
    m.second_rays = std::min(m.second_rays, e.second_rays);
    m.rings = std::min(m.rings, e.rings);
    m.image = std::min(m.image, e.image);
    m.elevation = std::max(m.elevation, e.elevation);
  }
  return m;
}

/// check_placement for every lidar of the search; stops at the first that fails.
std::vector<PlacementReport> check_all(const Scene& scene, const SensorSetting& setting,
                                       const std::vector<LidarModel>& lidars, const StereoRig& rig,
                                       const PlacementSearch& search, bool stop_at_failure) {
  std::vector<PlacementReport> reports;
  for (const LidarModel& lidar : lidars) {
    reports.push_back(check_placement(scene, lidar, setting, rig, search.requirements));
    if (stop_at_failure && !reports.back().ok) return reports;  // cheapest verdict first
  }
  for (const MountedLidar& extra : search.also) {
    reports.push_back(check_placement(scene, extra.model, extra.setting, rig, search.requirements));
    if (stop_at_failure && !reports.back().ok) return reports;
  }
  return reports;
}

Margins exact(const std::vector<PlacementReport>& reports, const PlacementRequirements& req) {
  Margins m{1 << 30, 1 << 30, 1e9, 0.0};
  for (const auto& r : reports) {
    if (r.ring_free) {
      for (int h = 0; h < 4; ++h) add_rosette_margins(r.returns_through_hole[h], r.returns_around_hole[h], req, &m);
    } else {
      m.second_rays = std::min(m.second_rays, r.min_rays_second_ring);
      m.rings = std::min(m.rings, *std::min_element(r.rings_per_hole.begin(), r.rings_per_hole.end()));
    }
    m.image = std::min(m.image, r.image_margin);
    m.elevation = std::max({m.elevation, r.normal_elevation_camera, r.normal_elevation_lidar});
  }
  return m;
}

}  // namespace

PlacementResult find_placement(const Target& target, const SensorSetting& setting,
                               const std::vector<LidarModel>& lidars, const StereoRig& rig,
                               const SceneLayout& layout, const PlacementSearch& search) {
  target.validate();
  rig.validate();
  if (lidars.empty()) throw ParamError("lidars", "need at least one lidar model");
  const PlacementRequirements& req = search.requirements;

  std::vector<BoardPose> poses;
  for (double x : search.distances)
    for (double y : search.lateral)
      for (double z : search.heights)
        for (double yaw : search.yaws)
          for (double pitch : search.pitches) poses.push_back(BoardPose{x, y, z, yaw, pitch, search.roll});
  if (poses.empty()) throw ParamError("placement_search", "empty grid");
  // Validate the layout here: workers must not throw.
  make_scene(target, poses.front(), layout);

  std::vector<double> estimated(poses.size());
  detail::parallel_for(static_cast<int>(poses.size()), search.threads, [&](int i) {
    estimated[i] = score(estimate_all(target, poses[i], setting, lidars, search.also, rig, req), req);
  }, 256);
  std::vector<int> order(poses.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return estimated[a] > estimated[b]; });

  PlacementResult result;
  result.score = -1e18;
  int best = order.front();
  bool found = false;
  const std::size_t checked = search.max_checked > 0 ? std::min<std::size_t>(search.max_checked, order.size()) : order.size();
  for (std::size_t begin = 0; begin < checked && !found; begin += kBatch) {
    const int count = static_cast<int>(std::min<std::size_t>(kBatch, order.size() - begin));
    std::vector<double> scores(count, -1e18);
    std::vector<char> passed(count, 0);
    detail::parallel_for(count, search.threads, [&](int k) {
      const BoardPose& pose = poses[order[begin + k]];
      const Scene scene = make_scene(target, pose, layout);
      const std::vector<PlacementReport> reports = check_all(scene, setting, lidars, rig, search, true);
      if (!reports.back().ok) return;
      passed[k] = 1;
      scores[k] = score(exact(reports, req), req);
    }, 1);
    for (int k = 0; k < count; ++k) {
      // Ties go to the better estimate, then to grid order (stable sort above).
      if (passed[k] && scores[k] > result.score) {
        result.score = scores[k];
        best = order[begin + k];
        found = true;
      }
    }
  }

  result.found = found;
  result.pose = poses[best];
  if (!found) result.score = estimated[best];
  const Scene scene = make_scene(target, result.pose, layout);
  result.reports = check_all(scene, setting, lidars, rig, search, false);
  return result;
}

}  // namespace l2s::sim
