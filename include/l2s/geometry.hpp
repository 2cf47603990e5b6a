#pragma once
// Geometric data the calibration stages hand each other.

#include <l2s/target.hpp>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <vector>

namespace l2s {

/// A plane n . p + d = 0 with unit normal, in the frame of the cloud it was fitted to.
using Plane = Eigen::Hyperplane<double, 3>;

/// A circle in 3D: the rim of one hole as a sensor saw it.
struct Circle {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();  ///< [m]
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  ///< unit, plane normal
  double radius = 0.0;                                 ///< [m]
};

/// Where a lidar ring crossed the rim of a hole: the rim lies somewhere
/// between the ring's last board return and its next ray (the next return's
/// azimuth, or one azimuth step on when nothing came back), both cut with the
/// sweep's board plane. The interval is an azimuth step wide; the midpoint is
/// the edge point the circle finder fits.
struct RimCrossing {
  Eigen::Vector3d board_side = Eigen::Vector3d::Zero();  ///< [m] sensor frame, on the board
  Eigen::Vector3d hole_side = Eigen::Vector3d::Zero();   ///< [m] sensor frame, over the hole
};

/// The four hole centres of one board, indexed by enum Hole (TL, TR, BL, BR).
using HoleCenters = std::array<Eigen::Vector3d, 4>;

inline const Eigen::Vector3d& at(const HoleCenters& centers, Hole hole) {
  return centers[static_cast<int>(hole)];
}

/// Points of the stereo cloud, each with the left-image pixel it came from so
/// that image edges can be looked up for it.
struct StereoCloud {
  std::vector<Eigen::Vector3d> points;  ///< [m] left optical frame (x right, y down, z forward)
  std::vector<Eigen::Vector2i> pixels;  ///< [px] (column, row) in the left image
  std::size_t size() const { return points.size(); }
};

}  // namespace l2s
