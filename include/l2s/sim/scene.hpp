#pragma once
// The static world of the synthetic test suite (paper, Sec. IV-A): the
// calibration board with its four through-holes, a wall a few metres behind
// it, the ground under the sensors and clutter boxes to the side. Optional
// elements make it look like a real recording: a stand under the board, the
// side walls of a corridor, low clutter between the sensors and the board and
// a pillar. Everything is given in the camera body frame (x forward, y left,
// z up, origin at the left camera's optical centre).

#include <l2s/export.hpp>
#include <l2s/target.hpp>

#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

namespace l2s::sim {

/// What a ray hit; also the value of the renderer's per-pixel label map.
enum class SurfaceId : std::uint8_t {
  None = 0,
  Board = 1,
  Wall = 2,
  Ground = 3,
  Clutter = 4,
  Stand = 5,     ///< post and base holding the board
  SideWall = 6,  ///< corridor walls parallel to the driving direction
  Pillar = 7,
};

/// Where the board sits: the centre of its front face in the camera body frame
/// and its attitude relative to a board that squarely faces the camera
/// (normal along -x_body, board x along -y_body, board y along +z_body).
/// R_cambody_board = Rz(yaw) * Ry(pitch) * Rx(roll) * R_facing: roll turns the
/// board in its own plane, pitch tilts it back (positive: face turns up), yaw
/// turns it about the vertical.
struct L2S_SIM_EXPORT BoardPose {
  double x = 3.0;      ///< [m] forward
  double y = 0.0;      ///< [m] left
  double z = 0.0;      ///< [m] up
  double yaw = 0.0;    ///< [rad]
  double pitch = 0.0;  ///< [rad]
  double roll = 0.0;   ///< [rad]

  Eigen::Isometry3d T_cambody_board() const;
};

/// An oriented box: centre and axes from T_cambody_box, half extents per axis.
struct Box {
  Eigen::Isometry3d T_cambody_box = Eigen::Isometry3d::Identity();
  Eigen::Vector3d half_size = Eigen::Vector3d::Constant(0.5);  ///< [m]
};

/// How the scene around the board is laid out (defaults: the paper's world).
struct L2S_SIM_EXPORT SceneLayout {
  double camera_height = 1.5;     ///< [m] camera optical centre above the ground
  double wall_gap = 3.0;          ///< [m] wall front face behind the board centre, along body x
  double wall_half_width = 15.0;  ///< [m] wall extent to each side along body y
  double wall_top = 4.0;          ///< [m] top edge of the wall above the camera
  bool default_clutter = true;    ///< add the two boxes beside the board
  std::vector<Box> extra_clutter; ///< more boxes, camera body frame

  // Elements of real recordings; all off by default (the paper's world).
  bool board_stand = false;         ///< a post and a base under the board, touching its bottom edge
  double side_wall_distance = 0.0;  ///< [m] corridor walls at y_body = +-this, along x; 0 = none, else 0.8..20
  int near_clutter = 0;             ///< low boxes on the ground between the sensors and the board, 0..8
  bool pillar = false;              ///< a 0.4 m square pillar beside the board, ground to wall top

  /// Throws ParamError naming the field.
  void validate() const;
};

/// The world: board, wall, ground plane and clutter, in the camera body frame.
struct Scene {
  Target target;  ///< as built; its markers where they are glued (SimulationConfig::marker_gluing)
  std::vector<double> marker_turns;  ///< [rad] each marker's turn in the board plane about its centre (empty: none)
  Eigen::Isometry3d T_cambody_board = Eigen::Isometry3d::Identity();
  double ground_z = -1.5;  ///< [m] height of the ground plane (z_body)
  Box wall;
  std::vector<Box> clutter;     ///< SurfaceId::Clutter: beside the board and nearer than it
  std::vector<Box> stand;       ///< SurfaceId::Stand: post and base
  std::vector<Box> side_walls;  ///< SurfaceId::SideWall
  std::vector<Box> pillars;     ///< SurfaceId::Pillar
  double side_wall_distance = 0.0;  ///< [m] as in SceneLayout, 0 = no side walls
};

/// Builds the world around a board at `pose`: the wall stands `wall_gap` behind
/// the board (perpendicular to body x), clutter boxes sit well to the side;
/// near clutter stays below the sight lines to the board (it never hides it
/// from sensors above the box tops). Throws ParamError when the target or
/// layout is invalid.
L2S_SIM_EXPORT Scene make_scene(const Target& target, const BoardPose& pose, const SceneLayout& layout = {});

}  // namespace l2s::sim
