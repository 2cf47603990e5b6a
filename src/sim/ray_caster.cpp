#include <l2s/sim/ray_caster.hpp>

#include "sim/board_geometry.hpp"

#include <algorithm>
#include <cmath>

namespace l2s::sim {

RayCaster::RayCaster(const Scene& scene)
    : scene_(scene),
      T_board_cambody_(scene.T_cambody_board.inverse()),
      hole_centers_(scene.target.hole_centers()) {
  const auto add = [this](SurfaceId surface, const Box& box) {
    solids_.push_back(Solid{surface, box.T_cambody_box, box.T_cambody_box.inverse(), box.half_size,
                            box.half_size.norm() + 1e-6});
  };
  add(SurfaceId::Wall, scene_.wall);
  for (const Box& box : scene_.clutter) add(SurfaceId::Clutter, box);
  for (const Box& box : scene_.stand) add(SurfaceId::Stand, box);
  for (const Box& box : scene_.side_walls) add(SurfaceId::SideWall, box);
  for (const Box& box : scene_.pillars) add(SurfaceId::Pillar, box);
  const Target& b = scene_.target;
  board_bound_radius_ =
      0.5 * std::sqrt(b.board_width * b.board_width + b.board_height * b.board_height +
                      4.0 * b.board_thickness * b.board_thickness) + 1e-6;
}

Hit RayCaster::cast(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction) const {
  Hit best;
  detail::LocalHit local;

  // Ground plane z = ground_z, seen from above only (sensors are above it).
  if (direction.z() < 0.0 && origin.z() > scene_.ground_z) {
    const double t = (scene_.ground_z - origin.z()) / direction.z();
    best.t = t;
    best.surface = SurfaceId::Ground;
    best.part = 0;
    best.normal = Eigen::Vector3d::UnitZ();
    const Eigen::Vector3d p = origin + t * direction;
    best.uv = Eigen::Vector2d(p.x(), p.y());
  }

  const auto take = [&](SurfaceId surface, const Eigen::Isometry3d& T_cambody_local) {
    best.t = local.t;
    best.surface = surface;
    best.part = local.part;
    best.normal = T_cambody_local.linear() * local.normal;
    best.uv = local.uv;
  };

  for (const Solid& solid : solids_) {
    const Eigen::Vector3d o = solid.T_box_cambody * origin;
    const Eigen::Vector3d d = solid.T_box_cambody.linear() * direction;
    if (detail::intersect_box(Eigen::Vector3d::Zero(), solid.half_size, o, d, best.t, &local))
      take(solid.surface, solid.T_cambody_box);
  }

  // Board, after a cheap bounding-sphere rejection (most rays miss it).
  const Eigen::Vector3d o = T_board_cambody_ * origin;
  const Eigen::Vector3d d = T_board_cambody_.linear() * direction;
  const Eigen::Vector3d oc = o - Eigen::Vector3d(0.0, 0.0, -0.5 * scene_.target.board_thickness);
  const double along = oc.dot(d);
  const double miss2 = oc.squaredNorm() - along * along;
  if (miss2 <= board_bound_radius_ * board_bound_radius_ &&
      detail::intersect_board(scene_.target, hole_centers_, o, d, best.t, &local))
    take(SurfaceId::Board, scene_.T_cambody_board);
  return best;
}

bool RayCaster::near_outline(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                             const Cone& cone, double t_limit) const {
  for (const Solid& solid : solids_)
    if (near_box_outline(solid, origin, direction, cone, t_limit)) return true;
  return near_board_outline(origin, direction, cone, t_limit);
}

bool RayCaster::near_box_outline(const Solid& solid, const Eigen::Vector3d& origin,
                                 const Eigen::Vector3d& direction, const Cone& cone, double t_limit) const {
  // Bounding sphere first, widened by the cone's radius at its far side.
  const Eigen::Vector3d oc = solid.T_cambody_box.translation() - origin;
  const double along = oc.dot(direction);
  const double R = solid.bound_radius;
  // Only outlines before t_limit matter, so the cone is never wider than there.
  const double rho = cone.radius0 + cone.slope * std::min(oc.norm() + R, t_limit);
  if (along + R + rho < 0.0 || along - R - rho > t_limit) return false;
  if (oc.squaredNorm() - along * along > (R + rho) * (R + rho)) return false;
  const Eigen::Vector3d o = solid.T_box_cambody * origin;
  const Eigen::Vector3d d = solid.T_box_cambody.linear() * direction;
  return detail::near_box_outline(solid.half_size, o, d, rho, t_limit);
}

bool RayCaster::near_board_outline(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                                   const Cone& cone, double t_limit) const {
  const Eigen::Vector3d o = T_board_cambody_ * origin;
  const Eigen::Vector3d d = T_board_cambody_.linear() * direction;
  const Eigen::Vector3d oc = o - Eigen::Vector3d(0.0, 0.0, -0.5 * scene_.target.board_thickness);
  const double along = oc.dot(d);
  const double rho = cone.radius0 + cone.slope * std::min(oc.norm() + board_bound_radius_, t_limit);
  const double reach = board_bound_radius_ + rho / std::max(0.05, std::abs(d.z()));
  if (oc.squaredNorm() - along * along > reach * reach) return false;
  return detail::near_board_outline(scene_.target, hole_centers_, o, d, cone.radius0, cone.slope, t_limit);
}

int RayCaster::hole_on_front_plane(const Eigen::Vector3d& origin,
                                   const Eigen::Vector3d& direction) const {
  const Eigen::Vector3d o = T_board_cambody_ * origin;
  const Eigen::Vector3d d = T_board_cambody_.linear() * direction;
  if (std::abs(d.z()) < 1e-12) return -1;
  const double t = -o.z() / d.z();
  if (t <= 0.0) return -1;
  const Eigen::Vector2d p = (o + t * d).head<2>();
  const double r2 = scene_.target.hole_radius * scene_.target.hole_radius;
  for (int h = 0; h < 4; ++h)
    if ((p - hole_centers_[static_cast<std::size_t>(h)]).squaredNorm() < r2) return h;
  return -1;
}

}  // namespace l2s::sim
