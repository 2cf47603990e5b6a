// Scene elements of real recordings. The stand, walls and boxes are plain
// oriented boxes; where they go is chosen so that the board stays usable:
// the stand stays below the lowest hole, near clutter below every sight line,
// the pillar out of the rays through the holes.

#include "sim/scene_elements.hpp"

#include <l2s/sim/settings.hpp>

#include <algorithm>
#include <cmath>

namespace l2s::sim::detail {
namespace {

/// Lowest z of the board's corners (front and back), camera body frame.
double board_lowest_z(const Scene& scene) {
  const Target& t = scene.target;
  double lowest = 1e9;
  for (double sx : {-0.5, 0.5})
    for (double sy : {-0.5, 0.5})
      for (double z : {0.0, -t.board_thickness})
        lowest = std::min(lowest, (scene.T_cambody_board *
                                   Eigen::Vector3d(sx * t.board_width, sy * t.board_height, z)).z());
  return lowest;
}

}  // namespace

Box ground_box(double center_x, double center_y, double ground_z, const Eigen::Vector3d& size, double yaw) {
  Box box;
  box.T_cambody_box = Eigen::Isometry3d::Identity();
  box.T_cambody_box.linear() = rotation_zyx(yaw, 0.0, 0.0);
  box.T_cambody_box.translation() = Eigen::Vector3d(center_x, center_y, ground_z + 0.5 * size.z());
  box.half_size = 0.5 * size;
  return box;
}

void add_board_stand(const BoardPose& pose, Scene* scene) {
  const Target& t = scene->target;
  // The post's top stays 3 cm below the lowest hole rim, so no ray through a
  // hole can end on it, and at least 2 cm above the bottom edge (it holds the board).
  double lowest_rim = 1e9;
  for (const Eigen::Vector2d& c : t.hole_centers()) lowest_rim = std::min(lowest_rim, c.y() - t.hole_radius);
  const double bottom = -0.5 * t.board_height;
  const double top_y = std::max(bottom + 0.02, std::min(bottom + 0.15, lowest_rim - 0.03));
  // The post stands just behind the back face, under the middle of the bottom edge.
  const double post = 0.04;
  const Eigen::Vector3d foot = scene->T_cambody_board * Eigen::Vector3d(0.0, bottom, -t.board_thickness - 0.5 * post);
  const double top_z = (scene->T_cambody_board * Eigen::Vector3d(0.0, top_y, -t.board_thickness)).z();
  const double height = top_z - scene->ground_z;
  if (height > 0.05)
    scene->stand.push_back(ground_box(foot.x(), foot.y(), scene->ground_z, Eigen::Vector3d(post, post, height), pose.yaw));
  // The base: a flat plate, wider along the board than across it.
  scene->stand.push_back(ground_box(foot.x(), foot.y(), scene->ground_z, Eigen::Vector3d(0.4, 0.6, 0.03), pose.yaw));
}

void add_side_walls(const SceneLayout& layout, const BoardPose& pose, Scene* scene) {
  const double d = layout.side_wall_distance;
  const double x_far = pose.x + layout.wall_gap;  // the far wall's front face
  const double x_near = -10.0;                    // well behind the sensors
  const double height = layout.wall_top - scene->ground_z;
  for (double side : {+1.0, -1.0}) {
    Box wall;
    wall.T_cambody_box = Eigen::Isometry3d::Identity();
    wall.T_cambody_box.translation() =
        Eigen::Vector3d(0.5 * (x_far + x_near), side * (d + 0.1), scene->ground_z + 0.5 * height);
    wall.half_size = Eigen::Vector3d(0.5 * (x_far - x_near), 0.1, 0.5 * height);
    scene->side_walls.push_back(wall);
  }
}

void add_near_clutter(int count, const BoardPose& pose, Scene* scene) {
  const double clearance = board_lowest_z(*scene) - 0.05 - scene->ground_z;
  const double height = std::min(0.45, clearance);
  if (height < 0.1 || count <= 0) return;
  const double corridor = scene->side_wall_distance > 0.0 ? scene->side_wall_distance : 1e9;
  for (int k = 0; k < count; ++k) {
    // Spread over 40..85 % of the way to the board (nearer ones hide under
    // the lowest beams), alternating sides, some in the middle.
    const double f = 0.4 + 0.45 * (k + 0.5) / count;
    const double side = (k % 2 == 0) ? 1.0 : -1.0;
    const double offset = (k % 3 == 2) ? 0.0 : side * (0.6 + 0.25 * (k / 2));
    const Eigen::Vector3d size(0.4 + 0.1 * (k % 3), 0.5 - 0.05 * (k % 2), height - 0.05 * (k % 2));
    double y = f * pose.y + offset;
    const double half = 0.5 * size.norm();
    y = std::clamp(y, -corridor + half + 0.05, corridor - half - 0.05);
    scene->clutter.push_back(ground_box(f * pose.x, y, scene->ground_z, size, 0.3 * side + 0.1 * k));
  }
}

void add_pillar(const SceneLayout& layout, const BoardPose& pose, Scene* scene) {
  const Target& t = scene->target;
  const double size = 0.4;
  // Beside the board on the side nearer the sensors' centre line, behind its plane.
  const double side = pose.y > 0.0 ? -1.0 : 1.0;
  double y = pose.y + side * (0.5 * t.board_width + 0.6 + 0.5 * size);
  if (layout.side_wall_distance > 0.0) {
    const double limit = layout.side_wall_distance - 0.5 * size;
    y = std::clamp(y, -limit, limit);
  }
  const double height = layout.wall_top - scene->ground_z;
  scene->pillars.push_back(ground_box(pose.x + 0.6 + 0.5 * size, y, scene->ground_z,
                                      Eigen::Vector3d(size, size, height), 0.0));
}

void fit_clutter_into_corridor(const BoardPose& pose, Scene* scene) {
  const double d = scene->side_wall_distance;
  const double board_band = 0.5 * scene->target.board_width + 0.3;
  std::vector<Box> kept;
  for (Box box : scene->clutter) {
    const double reach = box.half_size.head<2>().norm();
    double& y = box.T_cambody_box.translation().y();
    y = std::clamp(y, -d + reach + 0.05, d - reach - 0.05);
    if (std::abs(y - pose.y) - reach >= board_band) kept.push_back(box);
  }
  scene->clutter = kept;
}

}  // namespace l2s::sim::detail
