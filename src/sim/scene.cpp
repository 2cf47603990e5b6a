#include <l2s/sim/scene.hpp>

#include <l2s/error.hpp>
#include <l2s/sim/settings.hpp>

#include "sim/scene_elements.hpp"

#include <cmath>

namespace l2s::sim {
namespace {

Box make_box(const Eigen::Vector3d& center, const Eigen::Vector3d& size, double yaw) {
  Box box;
  box.T_cambody_box = Eigen::Isometry3d::Identity();
  box.T_cambody_box.linear() = rotation_zyx(yaw, 0.0, 0.0);
  box.T_cambody_box.translation() = center;
  box.half_size = 0.5 * size;
  return box;
}

}  // namespace

Eigen::Isometry3d BoardPose::T_cambody_board() const {
  // A board squarely facing the camera: board x -> -y_body, y -> +z_body, z -> -x_body.
  Eigen::Matrix3d R_facing;
  R_facing << 0, 0, -1,  //
      -1, 0, 0,          //
      0, 1, 0;
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = rotation_zyx(yaw, pitch, roll) * R_facing;
  T.translation() = Eigen::Vector3d(x, y, z);
  return T;
}

void SceneLayout::validate() const {
  if (!(camera_height > 0.0)) throw ParamError("scene.camera_height", "must be > 0 m");
  if (!(wall_gap > 0.5)) throw ParamError("scene.wall_gap", "the wall must stand more than 0.5 m behind the board");
  if (!(wall_half_width > 0.0)) throw ParamError("scene.wall_half_width", "must be > 0 m");
  if (!(wall_top > -camera_height)) throw ParamError("scene.wall_top", "must be above the ground");
  if (!(side_wall_distance == 0.0 || (side_wall_distance >= 0.8 && side_wall_distance <= 20.0)))
    throw ParamError("scene.side_wall_distance", "must be 0 (none) or 0.8..20 m");
  if (near_clutter < 0 || near_clutter > 8) throw ParamError("scene.near_clutter", "must be 0..8 boxes");
  for (const Box& box : extra_clutter)
    if (!(box.half_size.minCoeff() > 0.0)) throw ParamError("scene.clutter", "box sizes must be > 0");
}

Scene make_scene(const Target& target, const BoardPose& pose, const SceneLayout& layout) {
  target.validate();
  layout.validate();
  if (!(layout.wall_gap > target.board_thickness + 0.5))
    throw ParamError("scene.wall_gap", "the wall must stand more than 0.5 m behind the board");

  Scene scene;
  scene.target = target;
  scene.T_cambody_board = pose.T_cambody_board();
  scene.ground_z = -layout.camera_height;

  // The wall: a 0.2 m thick slab from the ground up, its front face wall_gap
  // behind the board centre, so every ray through a hole ends on it.
  const double wall_x = pose.x + layout.wall_gap;
  const double height = layout.wall_top - scene.ground_z;
  scene.wall.T_cambody_box = Eigen::Isometry3d::Identity();
  scene.wall.T_cambody_box.translation() =
      Eigen::Vector3d(wall_x + 0.1, 0.0, scene.ground_z + 0.5 * height);
  scene.wall.half_size = Eigen::Vector3d(0.1, layout.wall_half_width, 0.5 * height);

  if (layout.default_clutter) {
    // Two boxes standing on the ground well beside the board: they give the
    // segmentation other planes and edges without occluding the target.
    scene.clutter.push_back(make_box(
        Eigen::Vector3d(pose.x + 1.5, pose.y - 2.1, scene.ground_z + 0.5),
        Eigen::Vector3d(0.8, 0.8, 1.0), 0.4));
    scene.clutter.push_back(make_box(
        Eigen::Vector3d(pose.x + 2.0, pose.y + 2.7, scene.ground_z + 0.6),
        Eigen::Vector3d(1.0, 0.6, 1.2), -0.3));
  }
  scene.side_wall_distance = layout.side_wall_distance;
  if (layout.side_wall_distance > 0.0) {
    detail::fit_clutter_into_corridor(pose, &scene);
    detail::add_side_walls(layout, pose, &scene);
  }
  for (const Box& box : layout.extra_clutter) scene.clutter.push_back(box);
  detail::add_near_clutter(layout.near_clutter, pose, &scene);
  if (layout.board_stand) detail::add_board_stand(pose, &scene);
  if (layout.pillar) detail::add_pillar(layout, pose, &scene);
  return scene;
}

}  // namespace l2s::sim
