// The placement check: what the calibrator needs to see (paper, Sec. III-B/C).
// Image side: the board outline and all four holes inside both images with a
// margin, unoccluded, holes see-through. Lidar side (placement_lidar.cpp):
// rings across each hole, or returns through and around it for a ring-free
// lidar. Both sensors must see the board roughly vertical (the calibrator's
// alpha_plane test), and it must stand free of the ground and side walls.

#include <l2s/sim/placement.hpp>

#include <l2s/sim/ray_caster.hpp>

#include <l2s/error.hpp>

#include "sim/placement_lidar.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace l2s::sim {
namespace {

using detail::kHoleNames;

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

}  // namespace

std::string PlacementReport::summary() const {
  std::ostringstream s;
  s.precision(3);
  const auto four = [&](const std::array<int, 4>& v) {
    s << "[" << v[0] << " " << v[1] << " " << v[2] << " " << v[3] << "]";
  };
  s << (ok ? "placement ok" : "placement FAILS") << ": image margin " << image_margin << " px, ";
  if (ring_free) {
    s << "returns through holes ";
    four(returns_through_hole);
    s << ", around them ";
    four(returns_around_hole);
    s << ", rim in view [" << rim_in_view[0] << " " << rim_in_view[1] << " " << rim_in_view[2] << " "
      << rim_in_view[3] << "]";
  } else {
    s << "rings per hole ";
    four(rings_per_hole);
  }
  s << ", normal elevation camera " << normal_elevation_camera << " rad, lidar " << normal_elevation_lidar << " rad";
  for (const std::string& f : failures) s << "\n  - " << f;
  return s.str();
}

PlacementReport check_placement(const Scene& scene, const LidarModel& lidar,
                                const SensorSetting& setting, const StereoRig& rig,
                                const PlacementRequirements& req) {
  if (!(req.accumulation_time > 0.0 && req.accumulation_time <= 60.0))
    throw ParamError("placement.accumulation_time", "must be in (0, 60] s");
  if (!(req.min_rim_in_view > 0.0 && req.min_rim_in_view <= 1.0))
    throw ParamError("placement.min_rim_in_view", "must be in (0, 1]");
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
  if (scene.side_wall_distance > 0.0) {
    double widest = 0.0;
    for (double sx : {-0.5, 0.5})
      for (double z : {0.0, -scene.target.board_thickness})
        widest = std::max(widest, std::abs((scene.T_cambody_board * Eigen::Vector3d(sx * scene.target.board_width, 0.0, z)).y()));
    if (widest > scene.side_wall_distance - 0.05)
      report.failures.push_back("board reaches into a side wall (" + std::to_string(widest) + " m from the centre line, walls at " +
                                std::to_string(scene.side_wall_distance) + " m)");
  }

  ImageCheck image;
  check_camera(caster, rig, 0, req, &image);
  check_camera(caster, rig, 1, req, &image);
  report.image_margin = image.margin;
  report.failures.insert(report.failures.end(), image.failures.begin(), image.failures.end());

  if (lidar.has_rings())
    detail::check_lidar_rings(caster, lidar, T_cambody_lidar, req, &report);
  else
    detail::check_lidar_rosette(caster, lidar, T_cambody_lidar, req, &report);
  report.ok = report.failures.empty();
  return report;
}

}  // namespace l2s::sim
