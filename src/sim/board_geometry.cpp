#include "sim/board_geometry.hpp"

#include <l2s/sim/ray_caster.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace l2s::sim::detail {
namespace {

/// Slab test: the interval [t_enter, t_exit] inside the box, and the axis and
/// side of the entry face.
bool slab_interval(const Eigen::Vector3d& center, const Eigen::Vector3d& half,
                   const Eigen::Vector3d& o, const Eigen::Vector3d& d, double* t_enter,
                   double* t_exit, int* axis, int* side) {
  double t0 = -std::numeric_limits<double>::infinity();
  double t1 = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 3; ++i) {
    const double lo = center[i] - half[i] - o[i];
    const double hi = center[i] + half[i] - o[i];
    if (std::abs(d[i]) < 1e-300) {
      if (lo > 0.0 || hi < 0.0) return false;  // parallel to the slab and outside it
      continue;
    }
    const double inv = 1.0 / d[i];
    double a = lo * inv;
    double b = hi * inv;
    int s = -1;  // entering through the low face
    if (a > b) {
      std::swap(a, b);
      s = +1;
    }
    if (a > t0) {
      t0 = a;
      *axis = i;
      *side = s;
    }
    t1 = std::min(t1, b);
    if (t0 > t1) return false;
  }
  *t_enter = t0;
  *t_exit = t1;
  return true;
}

Eigen::Vector2d other_axes(const Eigen::Vector3d& p, int axis) {
  if (axis == 0) return {p.y(), p.z()};
  if (axis == 1) return {p.x(), p.z()};
  return {p.x(), p.y()};
}

/// Distance from point c to the segment [a, b] in the plane.
double segment_distance(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  const Eigen::Vector2d ab = b - a;
  const double len2 = ab.squaredNorm();
  const double s = len2 > 0.0 ? std::clamp((c - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + s * ab - c).norm();
}

/// Whether the segment [a, b] meets the rectangle |p_i| <= half_i (2D slab test).
bool segment_meets_rectangle(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& half) {
  double s0 = 0.0, s1 = 1.0;
  const Eigen::Vector2d ab = b - a;
  for (int i = 0; i < 2; ++i) {
    if (std::abs(ab[i]) < 1e-300) {
      if (std::abs(a[i]) > half[i]) return false;
      continue;
    }
    double lo = (-half[i] - a[i]) / ab[i];
    double hi = (half[i] - a[i]) / ab[i];
    if (lo > hi) std::swap(lo, hi);
    s0 = std::max(s0, lo);
    s1 = std::min(s1, hi);
    if (s0 > s1) return false;
  }
  return true;
}

bool inside_rectangle(const Eigen::Vector2d& p, const Eigen::Vector2d& half) {
  return std::abs(p.x()) < half.x() && std::abs(p.y()) < half.y();
}

}  // namespace

bool intersect_box(const Eigen::Vector3d& center, const Eigen::Vector3d& half,
                   const Eigen::Vector3d& o, const Eigen::Vector3d& d, double t_max,
                   LocalHit* hit) {
  double t0 = 0.0, t1 = 0.0;
  int axis = 0, side = -1;
  if (!slab_interval(center, half, o, d, &t0, &t1, &axis, &side)) return false;
  if (t0 <= 0.0 || t0 >= t_max) return false;  // behind, inside, or beyond a closer hit
  hit->t = t0;
  hit->part = static_cast<std::uint8_t>(2 * axis + (side > 0 ? 1 : 0));
  hit->normal = Eigen::Vector3d::Zero();
  hit->normal[axis] = side;
  hit->uv = other_axes(o + t0 * d - center, axis);
  return true;
}

bool intersect_board(const Target& target, const std::array<Eigen::Vector2d, 4>& holes,
                     const Eigen::Vector3d& o, const Eigen::Vector3d& d, double t_max,
                     LocalHit* hit) {
  const Eigen::Vector3d center(0.0, 0.0, -0.5 * target.board_thickness);
  const Eigen::Vector3d half(0.5 * target.board_width, 0.5 * target.board_height,
                             0.5 * target.board_thickness);
  double t0 = 0.0, t1 = 0.0;
  int axis = 0, side = -1;
  if (!slab_interval(center, half, o, d, &t0, &t1, &axis, &side)) return false;
  if (t0 <= 0.0 || t0 >= t_max) return false;

  // Subtract the hole cylinders. The discs are disjoint, so the ray's line
  // lies inside at most one of them at t0, and leaving it puts the ray in solid.
  double t = t0;
  int hole_hit = -1;
  const double r = target.hole_radius;
  const double a = d.x() * d.x() + d.y() * d.y();
  for (int h = 0; h < 4; ++h) {
    const double ox = o.x() - holes[h].x();
    const double oy = o.y() - holes[h].y();
    const double c = ox * ox + oy * oy - r * r;
    if (a < 1e-300) {
      if (c < 0.0) return false;  // straight down the hole's axis
      continue;
    }
    const double b = 2.0 * (d.x() * ox + d.y() * oy);
    const double disc = b * b - 4.0 * a * c;
    if (disc <= 0.0) continue;
    const double sq = std::sqrt(disc);
    const double c0 = (-b - sq) / (2.0 * a);
    const double c1 = (-b + sq) / (2.0 * a);
    if (c0 <= t && t < c1) {
      t = c1;
      hole_hit = h;
      break;
    }
  }
  if (t >= t1 || t >= t_max) return false;  // passed through a hole

  hit->t = t;
  const Eigen::Vector3d p = o + t * d;
  if (hole_hit >= 0) {
    const Eigen::Vector2d radial = (p.head<2>() - holes[hole_hit]) / r;
    hit->part = static_cast<std::uint8_t>(BoardPart::HoleWall);
    hit->normal = Eigen::Vector3d(-radial.x(), -radial.y(), 0.0);  // faces the hole's axis
    hit->uv = Eigen::Vector2d(std::atan2(radial.y(), radial.x()) * r, p.z());
  } else if (axis == 2) {
    hit->part = static_cast<std::uint8_t>(side > 0 ? BoardPart::Front : BoardPart::Back);
    hit->normal = Eigen::Vector3d(0.0, 0.0, side);
    hit->uv = p.head<2>();
  } else {
    hit->part = static_cast<std::uint8_t>(BoardPart::Edge);
    hit->normal = Eigen::Vector3d::Zero();
    hit->normal[axis] = side;
    hit->uv = other_axes(p, axis);
  }
  return true;
}

bool near_box_outline(const Eigen::Vector3d& half, const Eigen::Vector3d& o, const Eigen::Vector3d& d,
                      double rho, double t_limit) {
  double t0 = 0.0, t1 = 0.0;
  int axis = 0, side = 0;
  const Eigen::Vector3d grown = half + Eigen::Vector3d::Constant(rho);
  if (!slab_interval(Eigen::Vector3d::Zero(), grown, o, d, &t0, &t1, &axis, &side)) return false;
  if (t1 <= 0.0 || t0 > t_limit) return false;
  const Eigen::Vector3d shrunk = half - Eigen::Vector3d::Constant(rho);
  if (shrunk.minCoeff() <= 0.0) return true;
  // A ray through the shrunk box keeps its whole beam on the box (the box is convex).
  return !slab_interval(Eigen::Vector3d::Zero(), shrunk, o, d, &t0, &t1, &axis, &side) || t1 <= 0.0;
}

bool near_board_outline(const Target& target, const std::array<Eigen::Vector2d, 4>& holes,
                        const Eigen::Vector3d& o, const Eigen::Vector3d& d, double radius0, double slope,
                        double t_limit) {
  const double thickness = target.board_thickness;
  const Eigen::Vector2d half(0.5 * target.board_width, 0.5 * target.board_height);
  // Nearly edge-on: the footprint smears over the board; say yes if the ray comes close at all.
  if (std::abs(d.z()) < 0.02) {
    const double rho = radius0 + slope * (o.norm() + half.norm());
    const Eigen::Vector3d grown(half.x() + rho, half.y() + rho, 0.5 * thickness + rho);
    double t0 = 0.0, t1 = 0.0;
    int axis = 0, side = 0;
    return slab_interval(Eigen::Vector3d(0.0, 0.0, -0.5 * thickness), grown, o, d, &t0, &t1, &axis, &side) &&
           t1 > 0.0 && t0 <= t_limit;
  }
  const double t_front = -o.z() / d.z();
  const double t_back = (-thickness - o.z()) / d.z();
  const double t_near = std::min(t_front, t_back);
  if (std::max(t_front, t_back) <= 0.0) return false;
  // The footprint on the board plane: the beam's radius, stretched by the incidence.
  const double rho = (radius0 + slope * std::max(t_front, t_back)) / std::abs(d.z());
  if (t_near - rho > t_limit) return false;  // hidden behind the centre ray's hit
  const Eigen::Vector2d a = (o + std::max(0.0, t_front) * d).head<2>();
  const Eigen::Vector2d b = (o + std::max(0.0, t_back) * d).head<2>();
  const Eigen::Vector2d grown = half + Eigen::Vector2d::Constant(rho);
  if (!segment_meets_rectangle(a, b, grown)) return false;
  const Eigen::Vector2d shrunk = half - Eigen::Vector2d::Constant(rho);
  if (!(shrunk.minCoeff() > 0.0 && inside_rectangle(a, shrunk) && inside_rectangle(b, shrunk))) return true;
  const double r = target.hole_radius;
  for (const Eigen::Vector2d& c : holes) {
    const double closest = segment_distance(a, b, c);
    const double farthest = std::max((a - c).norm(), (b - c).norm());
    if (closest < r + rho && farthest > r - rho) return true;
  }
  return false;
}

}  // namespace l2s::sim::detail
