#pragma once
// A camera pixel integrates the surface over its footprint: detail finer than
// the footprint shades as its mean instead of aliasing. Textures scale each
// component of wavelength L by what a Gaussian pixel of footprint w keeps of a
// sinusoid, exp(-2 pi^2 (w/2)^2 / L^2).

#include <cmath>

namespace l2s::sim::detail {

/// Share of a sinusoid of wavelength `wavelength` [m] a pixel of `footprint` [m] keeps.
inline double kept_amplitude(double footprint, double wavelength) {
  const double ratio = 0.5 * footprint / wavelength;
  return std::exp(-2.0 * 9.869604401089358 * ratio * ratio);
}

}  // namespace l2s::sim::detail
