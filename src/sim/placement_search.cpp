// Deterministic search for a board pose that passes check_placement for every
// lidar model, keeping the one with the most margin (rays through the
// second-best ring of the worst hole, rings per hole, image margin,
// verticality). Ray-cast checks cost about a millisecond, so every grid pose
// is first rated by a closed-form estimate of the same margins; the exact
// check then runs on the best-rated poses, batch by batch, until some pass.

#include <l2s/sim/placement.hpp>

#include <l2s/error.hpp>

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

/// Closed-form margins: projected corners, hole discs as seen from the lidar
/// (rings within the hole's angular radius, chord length per ring). No ray casting.
Margins estimate(const Target& target, const BoardPose& pose, const SensorSetting& setting,
                 const std::vector<LidarModel>& lidars, const StereoRig& rig) {
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
      std::vector<int> rays;
      for (double el : lidar.elevations) {
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

Margins exact(const std::vector<PlacementReport>& reports) {
  Margins m{1 << 30, 1 << 30, 1e9, 0.0};
  for (const auto& r : reports) {
    m.second_rays = std::min(m.second_rays, r.min_rays_second_ring);
    m.rings = std::min(m.rings, *std::min_element(r.rings_per_hole.begin(), r.rings_per_hole.end()));
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
    estimated[i] = score(estimate(target, poses[i], setting, lidars, rig), req);
  }, 256);
  std::vector<int> order(poses.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return estimated[a] > estimated[b]; });

  PlacementResult result;
  result.score = -1e18;
  int best = order.front();
  bool found = false;
  for (std::size_t begin = 0; begin < order.size() && !found; begin += kBatch) {
    const int count = static_cast<int>(std::min<std::size_t>(kBatch, order.size() - begin));
    std::vector<double> scores(count, -1e18);
    std::vector<char> passed(count, 0);
    detail::parallel_for(count, search.threads, [&](int k) {
      const BoardPose& pose = poses[order[begin + k]];
      const Scene scene = make_scene(target, pose, layout);
      std::vector<PlacementReport> reports;
      for (const LidarModel& lidar : lidars) {
        reports.push_back(check_placement(scene, lidar, setting, rig, req));
        if (!reports.back().ok) return;  // cheapest verdict first: the first model fails
      }
      passed[k] = 1;
      scores[k] = score(exact(reports), req);
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
  for (const LidarModel& lidar : lidars)
    result.reports.push_back(check_placement(scene, lidar, setting, rig, req));
  return result;
}

}  // namespace l2s::sim
