#pragma once
// Ray intersection with the two solids of the scene, in their own frames:
// an axis-aligned box, and the board (a box minus four cylinders along z);
// and whether a widening beam around a ray comes near their outlines.

#include <l2s/target.hpp>

#include <Eigen/Core>
#include <array>
#include <cstdint>

namespace l2s::sim::detail {

/// A hit in the solid's own frame.
struct LocalHit {
  double t = 0.0;                    ///< ray parameter
  std::uint8_t part = 0;             ///< face: BoardPart for the board, 2*axis+(side>0) for boxes
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  ///< outward, local frame
  Eigen::Vector2d uv = Eigen::Vector2d::Zero();      ///< [m] surface coordinates
};

/// Entry into the box |p_i - center_i| <= half_i along o + t d, t in (0, t_max).
bool intersect_box(const Eigen::Vector3d& center, const Eigen::Vector3d& half,
                   const Eigen::Vector3d& o, const Eigen::Vector3d& d, double t_max,
                   LocalHit* hit);

/// First hit on the board solid (board frame: front face z = 0, solid z in
/// [-thickness, 0]) minus the hole cylinders: a ray that enters a hole hits
/// the hole's inner wall or passes through.
bool intersect_board(const Target& target, const std::array<Eigen::Vector2d, 4>& holes,
                     const Eigen::Vector3d& o, const Eigen::Vector3d& d, double t_max,
                     LocalHit* hit);

/// Whether a beam of radius `rho` around the ray o + t d straddles the outline
/// of the box |p_i| <= half_i before `t_limit`: it meets the box grown by rho
/// but does not pass through the box shrunk by rho. Conservative.
bool near_box_outline(const Eigen::Vector3d& half, const Eigen::Vector3d& o, const Eigen::Vector3d& d,
                      double rho, double t_limit);

/// The same for the board (frame of intersect_board), its outer border and
/// hole rims, for a beam of radius radius0 + slope * t: the ray's path
/// through the slab, projected on the board plane, comes within the beam's
/// footprint of a border or rim. Conservative.
bool near_board_outline(const Target& target, const std::array<Eigen::Vector2d, 4>& holes,
                        const Eigen::Vector3d& o, const Eigen::Vector3d& d, double radius0, double slope,
                        double t_limit);

}  // namespace l2s::sim::detail
