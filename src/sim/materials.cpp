// Materials of the scene looks. Sizes are those of real materials: bricks
// about 215 x 65 mm with 10 mm mortar joints (running bond), tiles 0.1-0.3 m
// with thin grout, plywood grain a few millimetres apart along the board's
// long side. Fine detail is filtered by the pixel footprint w on the surface:
// a joint's coverage of [x - w/2, x + w/2] is integrated exactly, and a noise
// octave keeps what footprint_filter.hpp says of its amplitude. Printed board
// faces are in board_faces.cpp.

#include "sim/materials.hpp"

#include "sim/board_faces.hpp"
#include "sim/footprint_filter.hpp"
#include "sim/random.hpp"
#include "sim/texture.hpp"

#include <algorithm>
#include <cmath>

namespace l2s::sim::detail {
namespace {

constexpr double kTwoPi = 6.283185307179586;

/// Hash of two cell indices, uniform in [-1, 1].
double cell_hash(std::int64_t i, std::int64_t j, std::uint64_t seed) {
  const std::uint64_t h = mix64(seed ^ mix64(static_cast<std::uint64_t>(i) * 0x9E3779B97F4A7C15ULL +
                                             static_cast<std::uint64_t>(j)));
  return static_cast<double>(h >> 11) * (2.0 / 9007199254740992.0) - 1.0;
}

/// Share of [x - w/2, x + w/2] covered by joints of width `joint` that start
/// every `period` (the integral of the joint indicator, differenced).
double joint_coverage(double x, double w, double period, double joint) {
  const auto integral = [&](double s) {
    const double cell = std::floor(s / period);
    return cell * joint + std::min(s - cell * period, joint);
  };
  if (w < 1e-9) return x - std::floor(x / period) * period < joint ? 1.0 : 0.0;
  return std::clamp((integral(x + 0.5 * w) - integral(x - 0.5 * w)) / w, 0.0, 1.0);
}

Albedo mix(const Albedo& a, const Albedo& b, double t) {
  return Albedo{a.gray + t * (b.gray - a.gray), a.tint + t * (b.tint - a.tint)};
}

/// Masonry: blocks of `length` x `height` with joints; running bond shifts
/// every other course by half a block.
Albedo masonry(const Eigen::Vector2d& uv, double footprint, double length, double height,
               double joint, bool running_bond, const Albedo& block, double block_variation,
               const Albedo& mortar, std::uint64_t seed) {
  const double px = length + joint, py = height + joint;
  const double course = std::floor(uv.y() / py);
  const double shift = running_bond && std::fmod(std::abs(course), 2.0) == 1.0 ? 0.5 * px : 0.0;
  const double s = uv.x() + shift;
  const double column = std::floor(s / px);
  const double joints = 1.0 - (1.0 - joint_coverage(uv.y(), footprint, py, joint)) *
                                  (1.0 - joint_coverage(s, footprint, px, joint));
  Albedo face = block;
  const double v = cell_hash(static_cast<std::int64_t>(column), static_cast<std::int64_t>(course), seed);
  face.gray *= 1.0 + block_variation * v;
  face.gray += 0.04 * filtered_noise(uv.x(), uv.y(), 0.04, 3, seed ^ 0xB1ULL, footprint);
  // Each block's colour drifts a little too (fired clay, glaze batches).
  const double hue = cell_hash(static_cast<std::int64_t>(column), static_cast<std::int64_t>(course),
                               seed ^ 0x7EULL);
  const Eigen::Array3d drifted = face.tint * (1.0 + 0.04 * hue * Eigen::Array3d(-1.0, 0.0, 1.0));
  face.tint = tint(drifted[0], drifted[1], drifted[2]);
  Albedo gap = mortar;
  gap.gray += 0.03 * filtered_noise(uv.x(), uv.y(), 0.02, 2, seed ^ 0x3AULL, footprint);
  return mix(face, gap, joints);
}

Albedo wood(const Eigen::Vector2d& uv, double footprint, std::uint64_t seed) {
  // Grain lines run along board x; a slow warp bends them.
  const double x = uv.x();
  const double y = uv.y() + 0.006 * value_noise(x / 0.35, uv.y() / 0.06, seed ^ 0x11ULL);
  constexpr double kRing = 0.009, kFine = 0.003, kStreak = 0.012, kBroad = 0.04;  // [m] across the grain
  const double rings = std::sin(kTwoPi * y / kRing) * kept_amplitude(footprint, kRing);
  const double fine = value_noise(x / 0.6, y / kFine, seed ^ 0x22ULL) * kept_amplitude(footprint, kFine);
  const double streaks = value_noise(x / 0.8, y / kStreak, seed ^ 0x44ULL) * kept_amplitude(footprint, kStreak);
  const double broad = value_noise(x / 0.25, y / kBroad, seed ^ 0x33ULL) * kept_amplitude(footprint, kBroad);
  return Albedo{std::clamp(0.50 + 0.07 * rings + 0.06 * fine + 0.09 * streaks + 0.06 * broad, 0.02, 0.98),
                tint(0.50, 0.80, 1.30)};
}

/// The paper suite's material of `hit` with a colour tint (neutral gray but for the clutter boxes).
Albedo suite_look(const Hit& hit, std::uint64_t seed) {
  const Albedo a{albedo(hit, seed), Eigen::Array3d::Ones()};
  if (hit.surface == SurfaceId::Clutter) return Albedo{a.gray, tint(0.60, 0.85, 1.20)};
  return a;
}

/// Surfaces this file does not know (later geometry): rough concrete.
Albedo concrete(const Hit& hit, double footprint, std::uint64_t seed) {
  const std::uint64_t s = mix64(seed ^ (static_cast<std::uint64_t>(hit.surface) * 131 + hit.part));
  return Albedo{std::clamp(0.45 + 0.3 * filtered_noise(hit.uv.x(), hit.uv.y(), 0.25, 5, s, footprint),
                           0.02, 0.98),
                tint(0.98, 1.0, 1.01)};
}

}  // namespace

Materials::Materials(const Appearance& appearance, std::uint64_t seed)
    : look_(appearance), seed_(seed) {
  // Mean wall reflectance of each background (joints included).
  const double joint = look_.joint_width;
  switch (look_.background) {
    case Background::Textured: background_gray_ = 0.32; break;
    case Background::Bricks: {
      const double block = look_.brick_length * look_.brick_height;
      const double cell = (look_.brick_length + joint) * (look_.brick_height + joint);
      background_gray_ = 0.30 * block / cell + 0.55 * (1.0 - block / cell);
      break;
    }
    case Background::Tiles: background_gray_ = 0.70; break;
    case Background::Plain: background_gray_ = 0.62; break;
    case Background::White: background_gray_ = 0.85; break;
  }
}

Albedo Materials::surface(const Hit& hit, double footprint) const {
  switch (hit.surface) {
    case SurfaceId::Board: return board(hit, footprint);
    case SurfaceId::Wall: return wall(hit, footprint);
    case SurfaceId::Ground:
    case SurfaceId::Clutter:
    case SurfaceId::Stand:
    case SurfaceId::SideWall:
    case SurfaceId::Pillar: return suite_look(hit, seed_);
    case SurfaceId::None: return sky(Eigen::Vector3d::UnitX());
    default: return concrete(hit, footprint, seed_);
  }
}

Albedo Materials::board(const Hit& hit, double footprint) const {
  switch (look_.board) {
    case BoardTexture::Matte: return suite_look(hit, seed_);
    case BoardTexture::WoodGrain: return wood(hit.uv, footprint, seed_);
    case BoardTexture::LowContrast: {
      // Just brighter than the background where there is room, else darker.
      const double base = background_gray_ + (background_gray_ < 0.8 ? 0.07 : -0.07);
      const std::uint64_t s = mix64(seed_ ^ (131ULL + hit.part));
      const double n = filtered_noise(hit.uv.x(), hit.uv.y(), 0.05, 3, s, footprint);
      return Albedo{std::clamp(base + 0.10 * n, 0.02, 0.98), Eigen::Array3d::Ones()};
    }
    case BoardTexture::Speckle:
    case BoardTexture::NoisePrint: {
      if (hit.part != static_cast<std::uint8_t>(BoardPart::Front)) return unprinted_board();
      return look_.board == BoardTexture::Speckle ? speckle_print(hit.uv, footprint, seed_)
                                                  : noise_print(hit.uv, footprint, seed_);
    }
    case BoardTexture::Chipboard: return chipboard(hit.uv, footprint, seed_);
    case BoardTexture::Black: return black_paint(hit.uv, footprint, seed_);
    case BoardTexture::White: return white_paint(hit.uv, footprint, seed_);
    case BoardTexture::Logo:
    case BoardTexture::Sticker: return suite_look(hit, seed_);  // decals: BoardDecals
    case BoardTexture::Glossy: return laminate(hit.uv, footprint, seed_);
  }
  return suite_look(hit, seed_);
}

Albedo Materials::wall(const Hit& hit, double footprint) const {
  const std::uint64_t s = mix64(seed_ ^ 0xA11ULL);
  switch (look_.background) {
    case Background::Textured: return suite_look(hit, seed_);
    case Background::Bricks:
      return masonry(hit.uv, footprint, look_.brick_length, look_.brick_height, look_.joint_width, true,
                     Albedo{0.30, tint(0.55, 0.75, 1.45)}, 0.15, Albedo{0.55, tint(0.95, 1.0, 1.04)}, s);
    case Background::Tiles:
      return masonry(hit.uv, footprint, look_.brick_length, look_.brick_length, look_.joint_width, false,
                     Albedo{0.72, tint(0.92, 1.0, 1.05)}, 0.04, Albedo{0.40, tint(1.0, 1.0, 1.0)}, s);
    case Background::Plain: {
      const double n = 0.02 * filtered_noise(hit.uv.x(), hit.uv.y(), 1.5, 2, s, footprint) +
                       0.006 * filtered_noise(hit.uv.x(), hit.uv.y(), 0.05, 2, s ^ 1ULL, footprint);
      return Albedo{0.62 + n, tint(0.92, 1.0, 1.05)};
    }
    case Background::White: {
      const double n = 0.015 * filtered_noise(hit.uv.x(), hit.uv.y(), 1.5, 2, s, footprint) +
                       0.005 * filtered_noise(hit.uv.x(), hit.uv.y(), 0.05, 2, s ^ 1ULL, footprint);
      return Albedo{0.85 + n, tint(0.98, 1.0, 1.01)};
    }
  }
  return suite_look(hit, seed_);
}

Albedo Materials::sky(const Eigen::Vector3d& direction) const {
  if (look_.sky == Sky::Uniform) return Albedo{0.9, Eigen::Array3d::Ones()};
  // Daylight: bright haze at the horizon, deeper blue overhead.
  const double up = std::clamp(direction.z(), 0.0, 1.0);
  const double t = std::sqrt(up);
  const Eigen::Array3d horizon = tint(1.05, 1.0, 0.95), zenith = tint(1.45, 1.0, 0.70);
  return Albedo{0.95 - 0.25 * t, horizon + t * (zenith - horizon)};
}

}  // namespace l2s::sim::detail
