#include "sim/texture.hpp"

#include "sim/random.hpp"

#include <algorithm>
#include <cmath>

namespace l2s::sim::detail {
namespace {

double lattice(std::int64_t i, std::int64_t j, std::uint64_t seed) {
  // One mixing round over a linear combination is plenty for texture noise.
  const std::uint64_t h = mix64(seed + static_cast<std::uint64_t>(i) * 0x9E3779B97F4A7C15ULL +
                                static_cast<std::uint64_t>(j) * 0xC2B2AE3D27D4EB4FULL);
  return static_cast<double>(h >> 11) * (2.0 / 9007199254740992.0) - 1.0;
}

/// Per-octave lattice rotations (cos, sin), computed once.
struct OctaveTurns {
  double c[8], s[8];
  OctaveTurns() {
    for (int k = 0; k < 8; ++k) {
      c[k] = std::cos(0.61 + 1.13 * k);
      s[k] = std::sin(0.61 + 1.13 * k);
    }
  }
};
const OctaveTurns kTurns;

double smooth(double t) { return t * t * (3.0 - 2.0 * t); }

/// Looks of each material: mean reflectance, texture contrast and the longest
/// texture wavelength. The board is much brighter than the wall so that its
/// border and hole rims give strong image edges, while its own texture
/// (1.25-5 cm features) stays weak enough not to produce edges of its own.
struct Material {
  double base;
  double contrast;
  double wavelength;  // [m]
  int octaves;
};

constexpr Material kBoard{0.80, 0.22, 0.05, 3};
constexpr Material kWall{0.32, 0.45, 0.40, 5};
constexpr Material kGround{0.28, 0.40, 0.30, 4};
constexpr Material kClutter{0.50, 0.40, 0.20, 4};
constexpr Material kStand{0.15, 0.20, 0.10, 2};
constexpr Material kSideWall{0.40, 0.40, 0.40, 5};
constexpr Material kPillar{0.55, 0.30, 0.30, 4};

}  // namespace

double value_noise(double x, double y, std::uint64_t seed) {
  const double fx = std::floor(x);
  const double fy = std::floor(y);
  const auto i = static_cast<std::int64_t>(fx);
  const auto j = static_cast<std::int64_t>(fy);
  const double sx = smooth(x - fx);
  const double sy = smooth(y - fy);
  const double v00 = lattice(i, j, seed);
  const double v10 = lattice(i + 1, j, seed);
  const double v01 = lattice(i, j + 1, seed);
  const double v11 = lattice(i + 1, j + 1, seed);
  const double a = v00 + sx * (v10 - v00);
  const double b = v01 + sx * (v11 - v01);
  return a + sy * (b - a);
}

double fractal_noise(double x, double y, double wavelength, int octaves, std::uint64_t seed) {
  double sum = 0.0;
  double norm = 0.0;
  double amplitude = 1.0;
  double frequency = 1.0 / wavelength;
  for (int k = 0; k < octaves; ++k) {
    // Turn each octave by an irrational-looking angle to hide the lattice axes.
    const double c = kTurns.c[k & 7], s = kTurns.s[k & 7];
    const double u = (c * x - s * y) * frequency;
    const double v = (s * x + c * y) * frequency;
    sum += amplitude * value_noise(u, v, seed + 0x632BE5ABULL * (k + 1));
    norm += amplitude;
    amplitude *= 0.5;
    frequency *= 2.0;
  }
  return sum / norm;
}

double albedo(const Hit& hit, std::uint64_t seed) {
  const Material* material = nullptr;
  switch (hit.surface) {
    case SurfaceId::Board: material = &kBoard; break;
    case SurfaceId::Wall: material = &kWall; break;
    case SurfaceId::Ground: material = &kGround; break;
    case SurfaceId::Clutter: material = &kClutter; break;
    case SurfaceId::Stand: material = &kStand; break;
    case SurfaceId::SideWall: material = &kSideWall; break;
    case SurfaceId::Pillar: material = &kPillar; break;
    case SurfaceId::None: return 0.9;
  }
  // Each surface and face draws its own noise field.
  const std::uint64_t surface_seed =
      mix64(seed ^ (static_cast<std::uint64_t>(hit.surface) * 131 + hit.part));
  const double n = fractal_noise(hit.uv.x(), hit.uv.y(), material->wavelength, material->octaves,
                                 surface_seed);
  return std::clamp(material->base + material->contrast * n, 0.02, 0.98);
}

}  // namespace l2s::sim::detail
