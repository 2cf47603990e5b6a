#include "sim/rosette_scan.hpp"

#include <complex>

namespace l2s::sim::detail {
namespace {

constexpr double kTwoPi = 6.283185307179586476925;
constexpr double kGolden = 0.6180339887498949;

}  // namespace

void rosette_angles(const RosetteScan& scan, std::uint64_t first, int count, std::vector<double>* azimuth,
                    std::vector<double>* elevation) {
  azimuth->assign(static_cast<std::size_t>(count), 0.0);
  elevation->assign(static_cast<std::size_t>(count), 0.0);
  const int lasers = scan.lasers;
  const double dt = static_cast<double>(lasers) / scan.point_rate;  // one laser's firing period
  const double el_mid = 0.5 * (scan.elevation_max + scan.elevation_min);
  const double el_half = 0.5 * (scan.elevation_max - scan.elevation_min);
  // The phasors advance by a fixed turn per firing of one laser: one complex
  // product per firing instead of four trigonometric calls.
  const std::complex<double> step_a = std::polar(1.0, scan.prism_rate_a * dt);
  const std::complex<double> step_b = std::polar(1.0, -scan.prism_rate_b * dt);
  for (int k = 0; k < lasers; ++k) {
    // The first firing of laser k at or after `first`.
    const std::uint64_t start = first + static_cast<std::uint64_t>((k - static_cast<int>(first % lasers) + lasers) % lasers);
    if (start >= first + static_cast<std::uint64_t>(count)) continue;
    const double t0 = static_cast<double>(start) / scan.point_rate;
    // Each laser sits at its own prism phases, so the lasers trace different passes.
    std::complex<double> pa = std::polar(1.0, scan.prism_rate_a * t0 + kTwoPi * k / lasers);
    std::complex<double> pb = std::polar(1.0, -(scan.prism_rate_b * t0 + kTwoPi * kGolden * k));
    const double head0 = scan.rotation_rate > 0.0 ? kTwoPi * k / lasers : 0.0;
    int firing = 0;
    for (std::uint64_t i = start; i < first + static_cast<std::uint64_t>(count); i += lasers, ++firing) {
      const std::complex<double> p = 0.5 * (pa + pb);  // inside the unit disc
      const double t = t0 + firing * dt;
      const std::size_t slot = static_cast<std::size_t>(i - first);
      (*azimuth)[slot] = head0 + scan.rotation_rate * t + scan.azimuth_half_width * p.real();
      (*elevation)[slot] = el_mid + el_half * p.imag();
      pa *= step_a;
      pb *= step_b;
    }
  }
}

}  // namespace l2s::sim::detail
