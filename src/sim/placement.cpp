// The placement check: what the calibrator needs to see (paper, Sec. III-B/C).
// Image side: the board outline and all four holes inside both images with a
// margin, unoccluded, holes see-through. Lidar side: for every hole, at least
// two rings whose rays pass through the hole onto the wall for any azimuth
// offset of the sweep, with board returns on both sides (the depth
// discontinuities the lidar hole detector looks for). Both sensors must see
// the board roughly vertical (the calibrator's alpha_plane test).

#include <l2s/sim/placement.hpp>

#include <l2s/sim/ray_caster.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace l2s::sim {
namespace {

const char* const kHoleNames[4] = {"TopLeft", "TopRight", "BottomLeft", "BottomRight"};

/// Samples per azimuth step when measuring a ring's path across a hole.
constexpr int kFine = 4;

/// Points on the board's outline and hole rims (front and back faces), board frame.
std::vector<Eigen::Vector3d> outline_points(const Target& target) {
  std::vector<Eigen::Vector3d> points;
  const double w = 0.5 * target.board_width, h = 0.5 * target.board_height;
  for (double z : {0.0, -target.board_thickness}) {
    for (int i = 0; i <= 8; ++i) {
      const double s = -1.0 + 2.0 * i / 8.0;
      points.emplace_back(s * w, h, z);
      points.emplace_back(s * w, -h, z);
      points.emplace_back(w, s * h, z);
      points.emplace_back(-w, s * h, z);
    }
  }
  return points;
}

struct ImageCheck {
  double margin = 1e9;
  std::vector<std::string> failures;
};

void check_camera(const RayCaster& caster, const StereoRig& rig, int index,
                  const PlacementRequirements& req, ImageCheck* out) {
  const Scene& scene = caster.scene();
  const char* name = index == 0 ? "left image" : "right image";
  const Eigen::Isometry3d T_cambody_optical = rig.T_cambody_optical(index);
  const Eigen::Isometry3d T_optical_board = T_cambody_optical.inverse() * scene.T_cambody_board;
  const Eigen::Vector3d eye = T_cambody_optical.translation();

  double margin = 1e9;
  for (const Eigen::Vector3d& p_board : outline_points(scene.target)) {
    const Eigen::Vector3d p = T_optical_board * p_board;
    // Through the model of the image that is written (lens distortion for raw images).
    const Eigen::Vector2d px = rig.project_optical(index, p);
    if (!(p.z() > 0.1) || !px.allFinite()) {
      margin = -1e9;
      break;
    }
    const double u = px.x(), v = px.y();
    margin = std::min({margin, u + 0.5, rig.width - 0.5 - u, v + 0.5, rig.height - 0.5 - v});
  }
  out->margin = std::min(out->margin, margin);
  if (margin < req.min_image_margin) {
    std::ostringstream s;
    s.precision(3);
    s << name << ": board outline " << margin << " px from the image border (need "
      << req.min_image_margin << ")";
    out->failures.push_back(s.str());
  }

  // The front face must be seen from the front and be free of occluders: probe
  // points just inside the outline and around each hole rim.
  const Eigen::Vector3d normal = scene.T_cambody_board.linear().col(2);
  if (normal.dot(eye - scene.T_cambody_board.translation()) <= 0.0) {
    out->failures.push_back(std::string(name) + ": sees the back of the board");
    return;
  }
  const Target& t = scene.target;
  std::vector<Eigen::Vector2d> probes;
  const double w = 0.5 * t.board_width - 0.02, h = 0.5 * t.board_height - 0.02;
  for (double sx : {-1.0, 0.0, 1.0})
    for (double sy : {-1.0, 0.0, 1.0})
      if (sx != 0.0 || sy != 0.0) probes.emplace_back(sx * w, sy * h);
  const auto holes = t.hole_centers();
  for (const Eigen::Vector2d& c : holes)
    for (int k = 0; k < 8; ++k) {
      const double a = k * 3.14159265358979 / 4.0;
      probes.push_back(c + (t.hole_radius + 0.02) * Eigen::Vector2d(std::cos(a), std::sin(a)));
    }
  int occluded = 0;
  for (const Eigen::Vector2d& q : probes) {
    const Eigen::Vector3d target_point = scene.T_cambody_board * Eigen::Vector3d(q.x(), q.y(), 0.0);
    const Eigen::Vector3d d = (target_point - eye).normalized();
    const Hit hit = caster.cast(eye, d);
    if (hit.surface != SurfaceId::Board || std::abs(hit.t - (target_point - eye).norm()) > 0.01)
      ++occluded;
  }
  if (occluded > 0)
    out->failures.push_back(std::string(name) + ": " + std::to_string(occluded) +
                            " probe points of the board face are occluded");
  for (int hole = 0; hole < 4; ++hole) {
    const Eigen::Vector3d c = scene.T_cambody_board * Eigen::Vector3d(holes[hole].x(), holes[hole].y(), 0.0);
    const Hit hit = caster.cast(eye, (c - eye).normalized());
    if (hit.surface == SurfaceId::Board)
      out->failures.push_back(std::string(name) + ": hole " + kHoleNames[hole] +
                              " is not see-through (its rim hides it)");
  }
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
  const double el = lidar.elevations[ring];
  const Eigen::Vector3d origin = T_cambody_lidar.translation();
  // 0 other, 1 board, 2 through onto the wall, 3 through onto something else.
  std::vector<int> cls(static_cast<std::size_t>(2 * n + 1));
  for (int i = -n; i <= n; ++i) {
    const double az = azimuth_center + i * fine;
    const Eigen::Vector3d dir = T_cambody_lidar.linear() *
        Eigen::Vector3d(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el));
    const Hit hit = caster.cast(origin, dir);
    int c = 0;
    if (hit.surface == SurfaceId::Board && hit.t >= lidar.min_range && hit.t <= lidar.max_range)
      c = 1;
    else if (hit.surface != SurfaceId::Board && caster.hole_on_front_plane(origin, dir) == hole)
      c = (hit.surface == SurfaceId::Wall && hit.t <= lidar.max_range) ? 2 : 3;
    cls[static_cast<std::size_t>(i + n)] = c;
  }
  // The longest run of samples through the hole.
  int best_begin = -1, best_len = 0;
  for (int i = 0; i < static_cast<int>(cls.size());) {
    if (cls[i] < 2) {
      ++i;
      continue;
    }
    int j = i;
    while (j < static_cast<int>(cls.size()) && cls[j] >= 2) ++j;
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

std::string PlacementReport::summary() const {
  std::ostringstream s;
  s.precision(3);
  s << (ok ? "placement ok" : "placement FAILS") << ": image margin " << image_margin
    << " px, rings per hole [" << rings_per_hole[0] << " " << rings_per_hole[1] << " "
    << rings_per_hole[2] << " " << rings_per_hole[3] << "], normal elevation camera "
    << normal_elevation_camera << " rad, lidar " << normal_elevation_lidar << " rad";
  for (const std::string& f : failures) s << "\n  - " << f;
  return s.str();
}

PlacementReport check_placement(const Scene& scene, const LidarModel& lidar,
                                const SensorSetting& setting, const StereoRig& rig,
                                const PlacementRequirements& req) {
  PlacementReport report;
  const RayCaster caster(scene);
  const Eigen::Isometry3d T_cambody_lidar = setting.T_cambody_lidar();
  const Eigen::Isometry3d T_lidar_cambody = T_cambody_lidar.inverse();

  // Attitude: the calibrator only accepts planes near-parallel to each sensor's vertical axis.
  const Eigen::Vector3d normal_body = scene.T_cambody_board.linear().col(2);
  const Eigen::Vector3d normal_lidar = T_lidar_cambody.linear() * normal_body;
  report.normal_elevation_camera = std::asin(std::clamp(std::abs(normal_body.z()), 0.0, 1.0));
  report.normal_elevation_lidar = std::asin(std::clamp(std::abs(normal_lidar.z()), 0.0, 1.0));
  std::ostringstream s;
  s.precision(3);
  if (report.normal_elevation_camera > req.max_normal_elevation) {
    s << "board normal " << report.normal_elevation_camera << " rad from horizontal in the camera frame (max "
      << req.max_normal_elevation << ")";
    report.failures.push_back(s.str());
  }
  if (report.normal_elevation_lidar > req.max_normal_elevation) {
    s.str("");
    s << lidar.name << ": board normal " << report.normal_elevation_lidar
      << " rad from horizontal in the lidar frame (max " << req.max_normal_elevation << ")";
    report.failures.push_back(s.str());
  }
  const Eigen::Vector3d to_lidar = (T_cambody_lidar.translation() - scene.T_cambody_board.translation()).normalized();
  if (std::acos(std::clamp(normal_body.dot(to_lidar), -1.0, 1.0)) > req.max_incidence)
    report.failures.push_back(lidar.name + ": sees the board edge-on or from behind");

  // The board stands free: its lowest corner clears the ground.
  double lowest = 1e9;
  for (double sx : {-0.5, 0.5})
    for (double sy : {-0.5, 0.5})
      for (double z : {0.0, -scene.target.board_thickness})
        lowest = std::min(lowest, (scene.T_cambody_board * Eigen::Vector3d(sx * scene.target.board_width,
                                                                           sy * scene.target.board_height, z)).z());
  if (lowest < scene.ground_z + 0.05) report.failures.push_back("board reaches into the ground");

  ImageCheck image;
  check_camera(caster, rig, 0, req, &image);
  check_camera(caster, rig, 1, req, &image);
  report.image_margin = image.margin;
  report.failures.insert(report.failures.end(), image.failures.begin(), image.failures.end());

  // Lidar: the rings that come near each hole.
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
    std::vector<int> rays;
    for (int ring = 0; ring < lidar.rings(); ++ring) {
      if (std::abs(lidar.elevations[ring] - elevation) > radius) continue;
      const RingCrossing crossing =
          cross_ring(caster, lidar, T_cambody_lidar, hole, ring, azimuth, half_window);
      if (crossing.rays_through == 0) continue;
      report.crossings.push_back(crossing);
      if (crossing.counts()) {
        ++report.rings_per_hole[hole];
        rays.push_back(crossing.rays_through);
      }
    }
    std::sort(rays.rbegin(), rays.rend());
    second_min = std::min(second_min, rays.size() >= 2 ? rays[1] : 0);
    if (report.rings_per_hole[hole] < req.min_rings_per_hole) {
      s.str("");
      s << lidar.name << ": hole " << kHoleNames[hole] << " crossed by " << report.rings_per_hole[hole]
        << " ring(s), need " << req.min_rings_per_hole << " (rings near it:";
      int listed = 0;
      for (const RingCrossing& rc : report.crossings) {
        if (rc.hole != hole) continue;
        s << " " << rc.ring << ":" << rc.rays_through << " rays" << (rc.board_both_sides ? "" : " no board both sides")
          << (rc.background_is_wall ? "" : " background not the wall");
        ++listed;
      }
      if (listed == 0) s << " none";
      s << ")";
      report.failures.push_back(s.str());
    }
  }
  report.min_rays_second_ring = second_min;
  report.ok = report.failures.empty();
  return report;
}

}  // namespace l2s::sim
