#pragma once
// A camera pixel integrates the surface over its footprint: detail finer than
// the footprint shades as its mean instead of aliasing. Textures scale each
// component of wavelength L by what a Gaussian pixel of footprint w keeps of a
// sinusoid, exp(-2 pi^2 (w/2)^2 / L^2).

#include "sim/texture.hpp"

#include <cmath>
#include <cstdint>

namespace l2s::sim::detail {

/// Share of a sinusoid of wavelength `wavelength` [m] a pixel of `footprint` [m] keeps.
inline double kept_amplitude(double footprint, double wavelength) {
  const double ratio = 0.5 * footprint / wavelength;
  return std::exp(-2.0 * 9.869604401089358 * ratio * ratio);
}

/// Share of a pixel of footprint `footprint` [m] covered by a shape whose
/// outline is `distance` [m] away (negative inside): a linear ramp across the
/// footprint, so printed edges shade like a pixel integrates them.
inline double edge_coverage(double distance, double footprint) {
  if (footprint <= 1e-9) return distance < 0.0 ? 1.0 : 0.0;
  const double share = 0.5 - distance / footprint;
  return share < 0.0 ? 0.0 : (share > 1.0 ? 1.0 : share);
}

/// fractal_noise with each octave attenuated by the footprint (not renormalised,
/// so unresolvable detail fades to the mean instead of aliasing).
inline double filtered_noise(double x, double y, double wavelength, int octaves, std::uint64_t seed,
                             double footprint) {
  double sum = 0.0, norm = 0.0, amplitude = 1.0, w = wavelength;
  for (int k = 0; k < octaves; ++k) {
    const double kept = kept_amplitude(footprint, w);
    if (kept > 1e-3) sum += amplitude * kept * value_noise(x / w, y / w, seed + 0x632BE5ABULL * (k + 1));
    norm += amplitude;
    amplitude *= 0.5;
    w *= 0.5;
  }
  return sum / norm;
}

}  // namespace l2s::sim::detail
