#pragma once
// Small plane helpers shared by the plane stages (private to the library).

#include <l2s/geometry.hpp>

#include <Eigen/Eigenvalues>
#include <cstddef>
#include <vector>

namespace l2s::detail {

/// Least-squares plane through points[indices]: centroid and the direction of
/// least variance. Needs at least three non-collinear points.
inline Plane fit_plane(const std::vector<Eigen::Vector3d>& points,
                       const std::vector<std::size_t>& indices) {
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (std::size_t i : indices) centroid += points[i];
  centroid /= static_cast<double>(indices.size());
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (std::size_t i : indices) {
    const Eigen::Vector3d q = points[i] - centroid;
    scatter.noalias() += q * q.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(scatter);
  return Plane(solver.eigenvectors().col(0).normalized(), centroid);
}

/// The same plane with its normal turned towards the sensor origin (offset > 0).
inline Plane facing_origin(const Plane& plane) {
  return plane.offset() < 0.0 ? Plane(-plane.normal(), -plane.offset()) : plane;
}

/// In-plane axes for an upright plane: `up` is the sensor axis projected into
/// the plane, `right` = up x normal (so x right, y up, z = normal, as Target's board frame).
struct PlaneAxes {
  Eigen::Vector3d right;
  Eigen::Vector3d up;
  Eigen::Vector3d normal;
};

inline PlaneAxes plane_axes(const Eigen::Vector3d& normal, const Eigen::Vector3d& axis) {
  PlaneAxes axes;
  axes.normal = normal.normalized();
  Eigen::Vector3d up = axis - axis.dot(axes.normal) * axes.normal;
  if (up.norm() < 1e-9) up = axes.normal.unitOrthogonal();  // plane facing straight up: any axis
  axes.up = up.normalized();
  axes.right = axes.up.cross(axes.normal);
  return axes;
}

}  // namespace l2s::detail
