#pragma once
// A tiny ray caster for the lidar-stage tests and benchmarks: one board with
// four through-holes (a slab of the Target's thickness), infinite planes for a
// wall and the ground, and a ring scanner like a VLP-16. Deliberately small
// and separate from l2s::sim, so these tests do not depend on the simulator.
// Header-only so that benchmarks can use it without a library of their own.

#include <l2s/geometry.hpp>
#include <l2s/target.hpp>
#include <l2s/types.hpp>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <random>
#include <vector>

namespace l2s::test {

constexpr double kDeg = M_PI / 180.0;
constexpr double kNoHit = std::numeric_limits<double>::infinity();

/// Board frame (Target convention: x right, y up, z out of the front face)
/// placed at `center`, front face turned to the sensor, then yawed about its
/// own y, pitched about its x and rolled about its z.
inline Eigen::Isometry3d board_pose(const Eigen::Vector3d& center, double yaw = 0.0, double pitch = 0.0,
                                    double roll = 0.0) {
  const Eigen::Vector3d z = -Eigen::Vector3d(center.x(), center.y(), 0.0).normalized();
  const Eigen::Vector3d y = Eigen::Vector3d::UnitZ();
  Eigen::Matrix3d R;
  R << y.cross(z), y, z;
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = R * Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitY()).toRotationMatrix() *
               Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitX()).toRotationMatrix() *
               Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = center;
  return T;
}

struct RingScanner {
  std::vector<double> elevations;  // [rad], ring 0 = lowest
  double azimuth_step = 0.2 * kDeg;
  double range_noise = 0.008;      // [m] sigma
  bool nan_for_no_return = false;  // emit NaN points for rays that hit nothing
};

inline RingScanner vlp16() {
  RingScanner s;
  for (int k = 0; k < 16; ++k) s.elevations.push_back((-15.0 + 2.0 * k) * kDeg);
  return s;
}

/// A 64-beam variant: -24.9..+2 deg, azimuth step 0.17 deg (about 135k points).
inline RingScanner beams64() {
  RingScanner s;
  for (int k = 0; k < 64; ++k) s.elevations.push_back((-24.9 + 26.9 * k / 63.0) * kDeg);
  s.azimuth_step = 0.17 * kDeg;
  return s;
}

struct Scene {
  Target target;
  Eigen::Isometry3d T_sensor_board = board_pose({3.0, 0.4, 0.03});
  bool has_board = true;
  std::vector<Plane> planes{Plane(Eigen::Vector3d::UnitX(), -6.0),   // wall at x = 6
                            Plane(Eigen::Vector3d::UnitZ(), 1.0)};   // ground at z = -1

  /// Range along the unit ray `d` from the sensor origin to the first surface.
  double cast(const Eigen::Vector3d& d) const {
    double best = cast_board(d);
    for (const Plane& p : planes) {
      const double denom = p.normal().dot(d);
      if (std::abs(denom) < 1e-12) continue;
      const double t = -p.offset() / denom;
      if (t > 0.0) best = std::min(best, t);
    }
    return best;
  }

  /// Range to the board slab (front/back face or a hole's wall), or kNoHit.
  double cast_board(const Eigen::Vector3d& d_sensor) const {
    if (!has_board) return kNoHit;
    const Eigen::Isometry3d T_board_sensor = T_sensor_board.inverse();
    const Eigen::Vector3d o = T_board_sensor.translation();
    const Eigen::Vector3d d = T_board_sensor.linear() * d_sensor;
    if (std::abs(d.z()) < 1e-12) return kNoHit;
    const double t_front = -o.z() / d.z();
    const double t_back = (-target.board_thickness - o.z()) / d.z();
    const double t_in = std::min(t_front, t_back), t_out = std::max(t_front, t_back);
    if (t_in <= 0.0) return kNoHit;
    const Eigen::Vector2d p_in = (o + t_in * d).head<2>();
    if (std::abs(p_in.x()) > target.board_width / 2 || std::abs(p_in.y()) > target.board_height / 2) return kNoHit;
    const double r = target.hole_radius;
    for (const Eigen::Vector2d& c : target.hole_centers()) {
      if ((p_in - c).norm() >= r) continue;
      if (((o + t_out * d).head<2>() - c).norm() < r) return kNoHit;  // straight through
      // Hits the hole's cylindrical wall: leave the circle between the faces.
      const Eigen::Vector2d oc = o.head<2>() - c, dxy = d.head<2>();
      const double a = dxy.squaredNorm(), b = oc.dot(dxy), cc = oc.squaredNorm() - r * r;
      return (-b + std::sqrt(std::max(0.0, b * b - a * cc))) / a;
    }
    return t_in;
  }

  /// Is the board's sensor-facing side its front face?
  bool sees_front() const { return T_sensor_board.inverse().translation().z() > 0.0; }

  /// Hole centres on the sensor-facing face, labelled as the sensor sees them:
  /// from behind, the board's own left and right swap.
  HoleCenters true_centers() const {
    const auto holes = target.hole_centers();
    const double z = sees_front() ? 0.0 : -target.board_thickness;
    static const int kFront[4] = {0, 1, 2, 3}, kBack[4] = {1, 0, 3, 2};
    HoleCenters out;
    for (int h = 0; h < 4; ++h) {
      const Eigen::Vector2d& c = holes[(sees_front() ? kFront : kBack)[h]];
      out[h] = T_sensor_board * Eigen::Vector3d(c.x(), c.y(), z);
    }
    return out;
  }

  /// The plane of the sensor-facing face.
  Plane visible_plane() const {
    const Eigen::Vector3d n = T_sensor_board.linear().col(2);
    return Plane(n, T_sensor_board * Eigen::Vector3d(0, 0, sees_front() ? 0.0 : -target.board_thickness));
  }
};

inline Eigen::Vector3d ray(double elevation, double azimuth) {
  return {std::cos(elevation) * std::cos(azimuth), std::cos(elevation) * std::sin(azimuth), std::sin(elevation)};
}

/// One full sweep, in ring-major azimuth order starting at -180 deg.
inline LidarCloud scan(const Scene& scene, const RingScanner& scanner, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, scanner.range_noise);
  LidarCloud cloud;
  const int steps = static_cast<int>(std::lround(2.0 * M_PI / scanner.azimuth_step));
  for (std::size_t k = 0; k < scanner.elevations.size(); ++k)
    for (int j = 0; j < steps; ++j) {
      const Eigen::Vector3d d = ray(scanner.elevations[k], -M_PI + j * scanner.azimuth_step);
      const double r = scene.cast(d);
      const double e = noise(rng);  // drawn for every ray: noise does not depend on the scene
      if (r == kNoHit && !scanner.nan_for_no_return) continue;
      cloud.points.push_back(r == kNoHit ? Eigen::Vector3d::Constant(std::nan("")) : Eigen::Vector3d(d * (r + e)));
      cloud.ring.push_back(static_cast<std::uint16_t>(k));
    }
  return cloud;
}

/// The same cloud in a seeded random order.
inline LidarCloud shuffled(const LidarCloud& cloud, std::uint64_t seed) {
  std::vector<std::size_t> order(cloud.size());
  std::iota(order.begin(), order.end(), 0);
  std::mt19937_64 rng(seed);
  std::shuffle(order.begin(), order.end(), rng);
  LidarCloud out;
  for (std::size_t i : order) out.points.push_back(cloud.points[i]), out.ring.push_back(cloud.ring[i]);
  return out;
}

/// Exact hole edges: per ring, the azimuths where the ray starts or stops
/// passing through a hole (bisection), as points on the sensor-facing face.
inline std::vector<Eigen::Vector3d> exact_hole_edges(const Scene& scene, const RingScanner& scanner) {
  const Plane face = scene.visible_plane();
  const auto on_face = [&](const Eigen::Vector3d& d) -> Eigen::Vector3d {
    return d * (-face.offset() / face.normal().dot(d));
  };
  // A ray "through a hole": misses the slab, yet meets the face inside the board outline.
  const auto through_hole = [&](const Eigen::Vector3d& d) {
    const double denom = face.normal().dot(d);
    if (scene.cast_board(d) != kNoHit || std::abs(denom) < 1e-9 || -face.offset() / denom <= 0.0) return false;
    const Eigen::Vector3d p = scene.T_sensor_board.inverse() * on_face(d);
    return std::abs(p.x()) < scene.target.board_width / 2 && std::abs(p.y()) < scene.target.board_height / 2;
  };
  std::vector<Eigen::Vector3d> edges;
  const double step = 0.05 * kDeg;
  for (double el : scanner.elevations)
    for (double az = -M_PI; az < M_PI; az += step) {
      const bool a = through_hole(ray(el, az)), b = through_hole(ray(el, az + step));
      if (a == b) continue;
      const bool a_on_board = scene.cast_board(ray(el, az)) != kNoHit;
      const bool b_on_board = scene.cast_board(ray(el, az + step)) != kNoHit;
      if (!(a || a_on_board) || !(b || b_on_board)) continue;  // the board's outline, not a hole
      double lo = az, hi = az + step;
      for (int i = 0; i < 60; ++i) {
        const double mid = 0.5 * (lo + hi);
        (through_hole(ray(el, mid)) == a ? lo : hi) = mid;
      }
      edges.push_back(on_face(ray(el, 0.5 * (lo + hi))));
    }
  return edges;
}

}  // namespace l2s::test
