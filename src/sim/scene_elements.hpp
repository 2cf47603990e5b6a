#pragma once
// The optional elements of real recordings (SceneLayout): a stand holding the
// board, the side walls of a corridor, low clutter between the sensors and
// the board, and a pillar beside it. Each adds boxes to a Scene whose board,
// ground and far wall are already placed.

#include <l2s/sim/scene.hpp>

namespace l2s::sim::detail {

/// A box standing on `ground_z`, `size` = (along its x, along its y, height),
/// turned by `yaw` about z; `center_xy` is its footprint centre.
Box ground_box(double center_x, double center_y, double ground_z, const Eigen::Vector3d& size, double yaw);

/// A 4 cm post from the ground up behind the board's bottom edge (holding it),
/// and a flat base on the ground under it.
void add_board_stand(const BoardPose& pose, Scene* scene);

/// Corridor walls at y = +-distance from behind the sensors to the far wall.
void add_side_walls(const SceneLayout& layout, const BoardPose& pose, Scene* scene);

/// `count` low boxes between the sensors and the board. Their tops stay 5 cm
/// below the board's lowest corner and at most 0.45 m above the ground, so no
/// straight line from a sensor above them to the board passes through them.
void add_near_clutter(int count, const BoardPose& pose, Scene* scene);

/// A square pillar 0.6 m behind the board plane, beside the board.
void add_pillar(const SceneLayout& layout, const BoardPose& pose, Scene* scene);

/// Moves the two default clutter boxes inside the corridor (against a side
/// wall), dropping one that would then stand behind the board.
void fit_clutter_into_corridor(const BoardPose& pose, Scene* scene);

}  // namespace l2s::sim::detail
