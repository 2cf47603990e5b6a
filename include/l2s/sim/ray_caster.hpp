#pragma once
// Exact ray casting against the scene. The board is constructive solid
// geometry: the slab of the board minus the four hole cylinders, so a ray
// through a hole reaches whatever lies behind it, the rim occludes part of the
// hole at oblique incidence and the hole's inner wall can be hit.

#include <l2s/export.hpp>
#include <l2s/sim/scene.hpp>

#include <Eigen/Core>
#include <cstdint>
#include <array>
#include <limits>
#include <vector>

namespace l2s::sim {

/// Which face of the board a ray hit (Hit::part when surface == Board).
enum class BoardPart : std::uint8_t { Front = 0, Back = 1, Edge = 2, HoleWall = 3 };

/// The first surface along a ray.
struct Hit {
  double t = std::numeric_limits<double>::infinity();  ///< [m] distance along the unit ray
  SurfaceId surface = SurfaceId::None;
  std::uint8_t part = 0;  ///< face within the surface (BoardPart for the board, box face index)
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  ///< unit, camera body frame, outward
  Eigen::Vector2d uv = Eigen::Vector2d::Zero();      ///< [m] coordinates on the surface (textures)

  bool hit() const { return surface != SurfaceId::None; }
};

/// A beam that widens along its way: everything within radius0 + slope * t
/// of the ray at distance t (a laser's footprint).
struct Cone {
  double radius0 = 0.0;  ///< [m] at the origin, >= 0
  double slope = 0.0;    ///< [m/m] growth per metre along the ray, >= 0
};

/// Casts rays into one Scene. Construction precomputes the inverse poses.
class L2S_SIM_EXPORT RayCaster {
 public:
  explicit RayCaster(const Scene& scene);

  /// First hit of the ray origin + t * direction, t > 0; direction must be unit.
  Hit cast(const Eigen::Vector3d& origin_cambody, const Eigen::Vector3d& direction_cambody) const;

  /// True when the cone around the ray may see more than one surface before
  /// `t_limit` (the centre ray's hit): some object's outline, or a hole rim,
  /// passes within the cone. Conservative (may say true needlessly, never
  /// false wrongly); the ground has no outline and only meets others in creases.
  bool near_outline(const Eigen::Vector3d& origin_cambody, const Eigen::Vector3d& direction_cambody,
                    const Cone& cone, double t_limit) const;

  /// Index (enum Hole) of the hole whose disc on the board's front plane the
  /// ray crosses, or -1 (also when the ray misses the front plane).
  int hole_on_front_plane(const Eigen::Vector3d& origin_cambody,
                          const Eigen::Vector3d& direction_cambody) const;

  const Scene& scene() const { return scene_; }

 private:
  /// A box of the scene with its inverse pose and bounding sphere.
  struct Solid {
    SurfaceId surface;
    Eigen::Isometry3d T_cambody_box;
    Eigen::Isometry3d T_box_cambody;
    Eigen::Vector3d half_size;
    double bound_radius;  ///< [m] sphere around the box centre
  };

  bool near_box_outline(const Solid& solid, const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                        const Cone& cone, double t_limit) const;
  bool near_board_outline(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, const Cone& cone,
                          double t_limit) const;

  Scene scene_;
  Eigen::Isometry3d T_board_cambody_;
  std::vector<Solid> solids_;  ///< wall, clutter, stand, side walls, pillars: the order of ties
  std::array<Eigen::Vector2d, 4> hole_centers_;
  double board_bound_radius_ = 0.0;  ///< [m] sphere around the board for early rejection
};

}  // namespace l2s::sim
