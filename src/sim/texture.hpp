#pragma once
// Procedural, deterministic surface textures for the renderer: multi-octave
// value noise in each surface's own 2D coordinates (metres), so that stereo
// matching finds texture everywhere and the same surface point looks the same
// from both cameras.

#include <l2s/sim/ray_caster.hpp>

#include <cstdint>

namespace l2s::sim::detail {

/// Value noise on a unit lattice in [-1, 1], smoothly interpolated.
double value_noise(double x, double y, std::uint64_t seed);

/// Sum of `octaves` value-noise layers, the first with wavelength
/// `wavelength` [m], each next one half as long and half as strong; roughly
/// in [-1, 1]. Each octave's lattice is turned, so no axis dominates.
double fractal_noise(double x, double y, double wavelength, int octaves, std::uint64_t seed);

/// Diffuse reflectance (0..1) of the surface point of `hit`; 0.9 for the sky.
double albedo(const Hit& hit, std::uint64_t seed);

}  // namespace l2s::sim::detail
