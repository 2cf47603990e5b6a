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

/// A coarse random-noise print: blotches of 1-3 cm from black to white, as
/// printed for stereo matching at longer range.
Albedo noise_print(const Eigen::Vector2d& uv, double footprint, std::uint64_t seed);

/// Oriented strand board: flakes of wood 4-8 cm long and 1.5-3 cm wide at
/// random angles, each of its own brightness, overlapping, with dark resin
/// between them.
Albedo chipboard(const Eigen::Vector2d& uv, double footprint, std::uint64_t seed);

/// A board painted matte black (reflectance 0.05), or matte white (0.86):
/// almost no texture of its own.
Albedo black_paint(const Eigen::Vector2d& uv, double footprint, std::uint64_t seed);
Albedo white_paint(const Eigen::Vector2d& uv, double footprint, std::uint64_t seed);

/// White laminate (0.80), its diffuse part; its gloss is a highlight the
/// shader adds (Shader, BoardTexture::Glossy).
Albedo laminate(const Eigen::Vector2d& uv, double footprint, std::uint64_t seed);

/// The board's edges, back and hole walls behind a printed front: plain
/// white foam board.
Albedo unprinted_board();

}  // namespace l2s::sim::detail
