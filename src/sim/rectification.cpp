// Stereo rectification (Bouguet's algorithm as described in OpenCV's
// stereoRectify documentation and Bradski & Kaehler, "Learning OpenCV",
// ch. 12): split the relative rotation in half between the cameras so that
// reprojection distortion is shared, then turn both about the same axis until
// the baseline is the rectified x axis. The rectified pinhole is chosen like
// alpha = 0 of cv::stereoRectify: the largest window that only holds pixels
// both raw images see.

#include "sim/rectification.hpp"

#include <l2s/error.hpp>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace l2s::sim::detail {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Raw pixels along the border of the valid raw area [0, W-1] x [0, H-1], by side.
struct Border {
  std::vector<Eigen::Vector2d> left, right, top, bottom;
};

Border raw_border(int width, int height, int step) {
  Border b;
  const double W = width - 1.0, H = height - 1.0;
  for (int v = 0;; v = std::min(v + step, height - 1)) {
    b.left.emplace_back(0.0, v);
    b.right.emplace_back(W, v);
    if (v == height - 1) break;
  }
  for (int u = 0;; u = std::min(u + step, width - 1)) {
    b.top.emplace_back(u, 0.0);
    b.bottom.emplace_back(u, H);
    if (u == width - 1) break;
  }
  return b;
}

/// Rectified normalised coordinates of raw pixel `px` of camera `index`.
Eigen::Vector2d rectified_normal(const StereoRig& rig, int index, const Eigen::Matrix3d& R,
                                 const Eigen::Vector2d& px) {
  const Eigen::Vector2d n = undistorted_normal(rig, index, px.x(), px.y());
  const Eigen::Vector3d q = R * Eigen::Vector3d(n.x(), n.y(), 1.0);
  if (!(q.z() > 0.0)) return {kNaN, kNaN};
  return q.head<2>() / q.z();
}

/// True when every rectified border pixel of the window K maps inside both raw images.
bool window_is_valid(const StereoRig& rig, const Rectification& rect, int step) {
  const Border border = raw_border(rig.width, rig.height, step);  // same pixels, rectified image
  const Eigen::Matrix3d K_inv = rect.K.inverse();
  for (int index = 0; index < 2; ++index) {
    const auto i = static_cast<std::size_t>(index);
    const Eigen::Matrix3d back = rect.R_rect_optical[i].transpose() * K_inv;
    const Eigen::Matrix3d K = rig.camera_matrix(index);
    const LensDistortion& lens = rig.lenses[i].distortion;
    double max_radius = 0.0;
    for (const auto* side : {&border.left, &border.right, &border.top, &border.bottom})
      for (const Eigen::Vector2d& px : *side) {
        const Eigen::Vector3d ray = back * px.homogeneous();
        if (!(ray.z() > 0.0)) return false;
        const Eigen::Vector2d n = ray.head<2>() / ray.z();
        max_radius = std::max(max_radius, n.norm());
        const Eigen::Vector2d d = lens.distort(n);
        const double u = K(0, 0) * d.x() + K(0, 2), v = K(1, 1) * d.y() + K(1, 2);
        if (!(u >= 0.0 && v >= 0.0 && u <= rig.width - 1.0 && v <= rig.height - 1.0)) return false;
      }
    // One check for the whole window: no border ray lies beyond a fold of the lens.
    if (!lens.one_to_one_up_to(max_radius)) return false;
  }
  return true;
}

bool same_lens(const CameraLens& a, const CameraLens& b) {
  return a.focal_scale == b.focal_scale && a.aspect == b.aspect &&
         a.principal_offset == b.principal_offset && a.distortion.model == b.distortion.model &&
         a.distortion.coefficients == b.distortion.coefficients;
}

bool same_rig(const StereoRig& a, const StereoRig& b) {
  return a.width == b.width && a.height == b.height && a.horizontal_fov == b.horizontal_fov &&
         a.baseline == b.baseline && same_lens(a.lenses[0], b.lenses[0]) &&
         same_lens(a.lenses[1], b.lenses[1]) && a.right_rotation == b.right_rotation &&
         a.right_offset == b.right_offset;
}

}  // namespace

Eigen::Vector2d undistorted_normal(const StereoRig& rig, int index, double u, double v) {
  const Eigen::Matrix3d K = rig.camera_matrix(index);
  const Eigen::Vector2d distorted((u - K(0, 2)) / K(0, 0), (v - K(1, 2)) / K(1, 1));
  return rig.lenses[static_cast<std::size_t>(index)].distortion.undistort(distorted);
}

Eigen::Vector2d raw_pixel(const StereoRig& rig, int index, const Eigen::Vector3d& ray_optical) {
  if (!(ray_optical.z() > 0.0)) return {kNaN, kNaN};
  const LensDistortion& lens = rig.lenses[static_cast<std::size_t>(index)].distortion;
  const Eigen::Vector2d n = ray_optical.head<2>() / ray_optical.z();
  if (!lens.one_to_one_up_to(n.norm())) return {kNaN, kNaN};
  const Eigen::Vector2d d = lens.distort(n);
  const Eigen::Matrix3d K = rig.camera_matrix(index);
  return {K(0, 0) * d.x() + K(0, 2), K(1, 1) * d.y() + K(1, 2)};
}

std::array<Eigen::Matrix3d, 2> rectifying_rotations(const StereoRig& rig) {
  // p_left = R_lr * p_right + t_lr. Turning the left camera by exp(-rho / 2)
  // and the right one by exp(+rho / 2) (rho = the rotation vector of R_lr)
  // gives both the same orientation, each half-way.
  const Eigen::Vector3d rho = rig.right_rotation;
  const double angle = rho.norm();
  const Eigen::Vector3d axis = angle > 0.0 ? Eigen::Vector3d(rho / angle) : Eigen::Vector3d::UnitX();
  const Eigen::Matrix3d half_left = Eigen::AngleAxisd(-0.5 * angle, axis).toRotationMatrix();
  const Eigen::Matrix3d half_right = Eigen::AngleAxisd(0.5 * angle, axis).toRotationMatrix();
  // The baseline (left centre -> right centre) in that common orientation,
  // turned onto +x by the smallest rotation.
  const Eigen::Vector3d t_lr = Eigen::Vector3d(rig.baseline, 0.0, 0.0) + rig.right_offset;
  const Eigen::Vector3d b = half_left * t_lr;
  const Eigen::Matrix3d W =
      Eigen::Quaterniond::FromTwoVectors(b.normalized(), Eigen::Vector3d::UnitX()).toRotationMatrix();
  return {W * half_left, W * half_right};
}

Rectification rectify(const StereoRig& rig) {
  Rectification rect;
  rect.R_rect_optical = rectifying_rotations(rig);
  rect.baseline = (Eigen::Vector3d(rig.baseline, 0.0, 0.0) + rig.right_offset).norm();

  const bool distorted = rig.lenses[0].distortion.model != DistortionModel::None ||
                         rig.lenses[1].distortion.model != DistortionModel::None;
  const int step = distorted ? 1 : std::max(rig.width, rig.height);
  const Border border = raw_border(rig.width, rig.height, step);
  double x_lo = -1e300, x_hi = 1e300, y_lo = -1e300, y_hi = 1e300;
  for (int index = 0; index < 2; ++index) {
    const Eigen::Matrix3d& R = rect.R_rect_optical[static_cast<std::size_t>(index)];
    const auto at = [&](const Eigen::Vector2d& px) { return rectified_normal(rig, index, R, px); };
    // NaN (a border ray behind the rectified camera) fails every comparison
    // below and so leaves the window empty: rejected.
    for (const auto& px : border.left) x_lo = std::max(x_lo, at(px).x());
    for (const auto& px : border.right) x_hi = std::min(x_hi, at(px).x());
    for (const auto& px : border.top) y_lo = std::max(y_lo, at(px).y());
    for (const auto& px : border.bottom) y_hi = std::min(y_hi, at(px).y());
  }
  if (!(x_hi > x_lo && y_hi > y_lo))
    throw ParamError("camera", "the two cameras share no rectified view");

  // Square pixels; the tighter of the two directions sets the focal length,
  // and the window is centred on the common area.
  double f = std::max((rig.width - 1.0) / (x_hi - x_lo), (rig.height - 1.0) / (y_hi - y_lo));
  for (int attempt = 0;; ++attempt) {
    rect.K << f, 0.0, (rig.width - 1.0) / 2.0 - f * 0.5 * (x_lo + x_hi),  //
        0.0, f, (rig.height - 1.0) / 2.0 - f * 0.5 * (y_lo + y_hi),        //
        0.0, 0.0, 1.0;
    // Between border samples a distorted edge may bulge a hair inwards; zoom
    // in by 0.1 % steps until every rectified border pixel is valid.
    if (window_is_valid(rig, rect, distorted ? 1 : std::max(rig.width, rig.height))) break;
    if (attempt == 100) throw ParamError("camera", "no valid rectified window found");
    f *= 1.001;
  }
  return rect;
}

const Rectification& rectify_cached(const StereoRig& rig) {
  struct Entry {
    bool valid = false;
    StereoRig rig;
    Rectification rectification;
  };
  thread_local Entry last;
  if (!last.valid || !same_rig(last.rig, rig)) {
    last.rectification = rectify(rig);  // may throw: the entry stays as it was
    last.rig = rig;
    last.valid = true;
  }
  return last.rectification;
}

}  // namespace l2s::sim::detail
