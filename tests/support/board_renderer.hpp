#pragma once
// A tiny ray-casting renderer for the camera-stage tests: a textured board with
// four through-holes (with thickness) in front of a darker textured wall, seen
// by an ideal rectified stereo pair. Pixels whose corners see different
// surfaces are supersampled, so edges carry exact area coverage and sub-pixel
// positions can be checked against ground truth. Header-only so that tests and
// benchmarks use it without a library of their own.

#include <l2s/camera.hpp>
#include <l2s/target.hpp>
#include <l2s/types.hpp>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

namespace l2s::test {

/// What the renderer draws; defaults give the paper's 1280x960 camera.
struct BoardScene {
  StereoCamera camera;
  Target target;
  Eigen::Isometry3d T_camera_board = Eigen::Isometry3d::Identity();
  bool with_board = true;
  double wall_depth = 5.0;     ///< [m] fronto-parallel wall, camera z
  double noise_sigma = 0.0;    ///< intensity noise, 0..1 scale
  std::uint32_t seed = 7;
  int supersampling = 8;       ///< per axis, on pixels crossed by a surface boundary
  /// Direction towards a light, camera frame; zero draws the holes' inner wall
  /// a flat 0.45. Otherwise the wall is Lambert-shaded (ambient 0.35), so the
  /// side a view sees through an oblique hole is lit or in shadow depending on
  /// which way the board is turned, as in the simulator.
  Eigen::Vector3d hole_wall_light = Eigen::Vector3d::Zero();
};

/// The simulator's light (above, behind and left of the cameras), camera optical frame.
inline Eigen::Vector3d simulator_light() { return Eigen::Vector3d(-0.35, -0.6, -1.0).normalized(); }

/// The ideal rectified pair of the paper's experiments (fx 1626 px, B 0.12 m).
inline StereoCamera make_stereo_camera(int width = 1280, int height = 960, double fx = 1626.0,
                                       double baseline = 0.12) {
  StereoCamera camera;
  const double cx = (width - 1) / 2.0, cy = (height - 1) / 2.0;
  camera.left = CameraInfo::ideal("left", width, height, fx, cx, cy, 0.0);
  camera.right = CameraInfo::ideal("right", width, height, fx, cx, cy, baseline);
  return camera;
}

/// Board facing the camera at (x, y, distance), then turned by `yaw` about
/// its own vertical axis and `pitch` about its horizontal axis [rad].
inline Eigen::Isometry3d board_pose(double distance, double yaw = 0.0, double pitch = 0.0,
                                    double x = 0.0, double y = 0.0) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  // Board x = camera x, board y (up) = -camera y, board z (to camera) = -camera z.
  const Eigen::Matrix3d R0 = Eigen::Vector3d(1, -1, -1).asDiagonal();
  T.linear() = R0 * Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitY()).toRotationMatrix() *
               Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitX()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(x, y, distance);
  return T;
}

namespace detail {

inline double hash01(int ix, int iy, std::uint32_t salt) {
  std::uint32_t h = static_cast<std::uint32_t>(ix) * 73856093u ^ static_cast<std::uint32_t>(iy) * 19349663u ^ salt * 83492791u;
  h ^= h >> 13; h *= 0x5bd1e995u; h ^= h >> 15;
  return (h & 0xffffffu) / double(0xffffff);
}

/// Smooth value noise in [0, 1] with cells of `cell` metres.
inline double value_noise(double x, double y, double cell, std::uint32_t salt) {
  const double fx = x / cell, fy = y / cell;
  const int ix = static_cast<int>(std::floor(fx)), iy = static_cast<int>(std::floor(fy));
  double ax = fx - ix, ay = fy - iy;
  ax = ax * ax * (3 - 2 * ax);
  ay = ay * ay * (3 - 2 * ay);
  const double a = hash01(ix, iy, salt), b = hash01(ix + 1, iy, salt);
  const double c = hash01(ix, iy + 1, salt), d = hash01(ix + 1, iy + 1, salt);
  return (1 - ay) * ((1 - ax) * a + ax * b) + ay * ((1 - ax) * c + ax * d);
}

struct Hit {
  int id;            // 0 wall, 1 board face, 2 hole wall, 3 board side
  double intensity;  // 0..1
};

/// First surface along origin + s * dir (camera frame).
inline Hit trace(const BoardScene& scene, const Eigen::Isometry3d& T_board_camera,
                 const std::array<Eigen::Vector2d, 4>& holes, const Eigen::Vector3d& origin,
                 const Eigen::Vector3d& dir) {
  if (scene.with_board) {
    const Eigen::Vector3d o = T_board_camera * origin;
    const Eigen::Vector3d d = T_board_camera.linear() * dir;
    const Target& t = scene.target;
    if (o.z() > 0.0 && d.z() < 0.0) {
      const Eigen::Vector3d front = o + (-o.z() / d.z()) * d;
      const Eigen::Vector3d back = o + ((-t.board_thickness - o.z()) / d.z()) * d;
      const auto in_rect = [&](const Eigen::Vector3d& p) {
        return std::abs(p.x()) <= t.board_width / 2 && std::abs(p.y()) <= t.board_height / 2;
      };
      const auto hole_of = [&](const Eigen::Vector3d& p) {
        for (int h = 0; h < 4; ++h)
          if ((p.head<2>() - holes[h]).norm() < t.hole_radius) return h;
        return -1;
      };
      if (in_rect(front)) {
        const int h = hole_of(front);
        if (h < 0) {
          const double n = 0.6 * value_noise(front.x(), front.y(), 0.01, 1) +
                           0.4 * value_noise(front.x(), front.y(), 0.04, 2);
          return {1, 0.5 + 0.25 * n};
        }
        if ((back.head<2>() - holes[h]).norm() >= t.hole_radius) {
          if (scene.hole_wall_light.isZero()) return {2, 0.45};
          // Where the ray meets the cylinder |p.xy - c| = r, going in from the front face.
          const Eigen::Vector2d f = front.head<2>() - holes[h], dxy = d.head<2>();
          const double a = dxy.squaredNorm(), b = f.dot(dxy), c = f.squaredNorm() - t.hole_radius * t.hole_radius;
          const double s = (-b + std::sqrt(std::max(0.0, b * b - a * c))) / a;
          const Eigen::Vector2d inward = -(f + s * dxy).normalized();  // faces the hole's axis, i.e. the viewer
          const Eigen::Vector3d normal_camera = T_board_camera.linear().transpose() * Eigen::Vector3d(inward.x(), inward.y(), 0.0);
          const double lambert = std::max(0.0, normal_camera.dot(scene.hole_wall_light.normalized()));
          return {2, 0.6 * (0.35 + 0.65 * lambert)};
        }
      } else if (in_rect(back) && hole_of(back) < 0) {
        return {3, 0.4};
      }
    }
  }
  const Eigen::Vector3d p = origin + ((scene.wall_depth - origin.z()) / dir.z()) * dir;
  const double n = 0.6 * value_noise(p.x(), p.y(), 0.01, 3) + 0.4 * value_noise(p.x(), p.y(), 0.04, 4);
  return {0, 0.08 + 0.2 * n};
}

}  // namespace detail

/// Renders one view: 0 = left, 1 = right. 8-bit gray.
inline Image render_view(const BoardScene& scene, int view) {
  const CameraInfo& cam = view == 0 ? scene.camera.left : scene.camera.right;
  const Eigen::Vector3d origin(view == 0 ? 0.0 : scene.camera.baseline(), 0.0, 0.0);
  const Eigen::Isometry3d T_board_camera = scene.T_camera_board.inverse();
  const auto holes = scene.target.hole_centers();
  const int W = cam.width, H = cam.height;
  const auto ray = [&](double u, double v) {
    return detail::trace(scene, T_board_camera, holes, origin,
                         Eigen::Vector3d((u - cam.cx()) / cam.fx(), (v - cam.cy()) / cam.fy(), 1.0));
  };
  std::vector<int> corner_id(static_cast<std::size_t>(W + 1) * (H + 1));
  for (int j = 0; j <= H; ++j)
    for (int i = 0; i <= W; ++i) corner_id[static_cast<std::size_t>(j) * (W + 1) + i] = ray(i - 0.5, j - 0.5).id;
  std::mt19937 rng(scene.seed + 1000u * view);
  std::normal_distribution<double> noise(0.0, scene.noise_sigma > 0 ? scene.noise_sigma : 1.0);
  Image image(W, H, 1);
  const int S = std::max(1, scene.supersampling);
  for (int j = 0; j < H; ++j)
    for (int i = 0; i < W; ++i) {
      const std::size_t c = static_cast<std::size_t>(j) * (W + 1) + i;
      const bool uniform = corner_id[c] == corner_id[c + 1] && corner_id[c] == corner_id[c + W + 1] &&
                           corner_id[c] == corner_id[c + W + 2];
      double value = 0.0;
      if (uniform) {
        value = ray(i, j).intensity;
      } else {
        for (int b = 0; b < S; ++b)
          for (int a = 0; a < S; ++a) value += ray(i - 0.5 + (a + 0.5) / S, j - 0.5 + (b + 0.5) / S).intensity;
        value /= S * S;
      }
      if (scene.noise_sigma > 0) value += noise(rng);
      image.at(i, j) = static_cast<std::uint8_t>(std::lround(std::clamp(value, 0.0, 1.0) * 255.0));
    }
  return image;
}

struct StereoPair {
  Image left, right;
};

inline StereoPair render_pair(const BoardScene& scene) { return {render_view(scene, 0), render_view(scene, 1)}; }

}  // namespace l2s::test
