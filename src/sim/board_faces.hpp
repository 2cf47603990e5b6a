#pragma once
// Printed board faces: what users put on the board's front so that stereo
// matching finds texture on it. Each is a function of the point on the face
// (board frame, metres, origin at the board's centre) and of the scene's seed,
// filtered by the pixel's footprint there like the other materials.

#include "sim/materials.hpp"

#include <Eigen/Core>
#include <cstdint>

namespace l2s::sim::detail {

/// A fine speckle print (as for digital image correlation): dark dots of
/// 2-4 mm radius, one at a random place in each 8 mm cell, on white paper.
Albedo speckle_print(const Eigen::Vector2d& uv, double footprint, std::uint64_t seed);

/// The board's edges, back and hole walls behind a printed front: plain
/// white foam board.
Albedo unprinted_board();

}  // namespace l2s::sim::detail
