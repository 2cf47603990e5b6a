#pragma once
// 2D coordinates on a board plane for diagnostics: what a user sees when
// facing the board from the sensor (u to the right, v up).

#include <l2s/geometry.hpp>

#include <Eigen/Geometry>
#include <vector>

namespace l2s::detail {

struct PlaneFrame {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  ///< [m] sensor frame, on the plane
  Eigen::Vector3d u = Eigen::Vector3d::UnitX();  ///< in-plane, to the right seen from the sensor
  Eigen::Vector3d v = Eigen::Vector3d::UnitY();  ///< in-plane, up
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  ///< towards the sensor

  /// Orthogonal projection of a sensor-frame point, [m] in the plane.
  Eigen::Vector2d to_plane(const Eigen::Vector3d& p) const {
    const Eigen::Vector3d d = p - origin;
    return {d.dot(u), d.dot(v)};
  }
  Eigen::Vector3d to_sensor(const Eigen::Vector2d& q) const {
    return origin + q.x() * u + q.y() * v;
  }
  /// Signed distance in front of the plane (towards the sensor) [m].
  double height(const Eigen::Vector3d& p) const { return (p - origin).dot(normal); }

  /// Frame on `plane` with `up` (sensor up axis) projected as v; origin at the
  /// projection of `centre` (e.g. the board points' centroid).
  static PlaneFrame make(const Plane& plane, const Eigen::Vector3d& up,
                         const Eigen::Vector3d& centre) {
    PlaneFrame f;
    f.normal = plane.normal().normalized();
    if (f.normal.dot(centre) > 0.0) f.normal = -f.normal;  // the sensor is at the origin
    Eigen::Vector3d v = up - up.dot(f.normal) * f.normal;
    if (v.norm() < 1e-9) v = f.normal.unitOrthogonal();  // plane facing up: any in-plane axis
    f.v = v.normalized();
    f.u = f.v.cross(f.normal);  // (u, v, normal) right-handed: u to the right seen from the sensor
    f.origin = plane.projection(centre);
    return f;
  }
};

/// Centroid of `points` at `indices` (all points when `indices` is empty); zero when none.
inline Eigen::Vector3d centroid(const std::vector<Eigen::Vector3d>& points,
                                const std::vector<std::size_t>& indices) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  std::size_t n = 0;
  const auto add = [&](const Eigen::Vector3d& p) {
    if (p.allFinite()) sum += p, ++n;
  };
  if (indices.empty())
    for (const auto& p : points) add(p);
  else
    for (const std::size_t i : indices) add(points[i]);
  return n > 0 ? Eigen::Vector3d(sum / static_cast<double>(n)) : Eigen::Vector3d::Zero();
}

}  // namespace l2s::detail
