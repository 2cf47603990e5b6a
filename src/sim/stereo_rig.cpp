#include <l2s/sim/stereo_rig.hpp>

#include <l2s/error.hpp>
#include <l2s/sim/settings.hpp>

#include "sim/rectification.hpp"

#include <cmath>
#include <limits>
#include <string>

namespace l2s::sim {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

const char* const kLensField[2] = {"camera.left", "camera.right"};

CameraInfo physical_info(const StereoRig& rig, int index, const detail::Rectification& rect) {
  const auto i = static_cast<std::size_t>(index);
  CameraInfo info;
  info.camera_name = index == 0 ? "left" : "right";
  info.width = rig.width;
  info.height = rig.height;
  info.camera_matrix = rig.camera_matrix(index);
  info.distortion_model = rig.lenses[i].distortion.ros_model();
  info.distortion_coefficients = rig.lenses[i].distortion.ros_coefficients();
  info.rectification_matrix = rect.R_rect_optical[i];
  info.projection_matrix.setZero();
  info.projection_matrix.leftCols<3>() = rect.K;
  // The right camera sits one baseline along rectified +x: P[0][3] = -f * B.
  if (index == 1) info.projection_matrix(0, 3) = -rect.K(0, 0) * rect.baseline;
  return info;
}

/// Undistorts raw points on the image border and checks the lens maps them
/// back (no fold before the border: every raw pixel has one ray).
void check_lens_covers_image(const StereoRig& rig, int index) {
  const LensDistortion& lens = rig.lenses[static_cast<std::size_t>(index)].distortion;
  if (lens.model == DistortionModel::None) return;
  // The nominal focal length comes from the radial profile at the field of
  // view's edge, which must lie before any fold.
  if (!lens.one_to_one_up_to(std::tan(0.5 * rig.horizontal_fov)))
    throw ParamError(std::string(kLensField[index]) + ".distortion",
                     "the lens model folds over within the field of view");
  const Eigen::Matrix3d K = rig.camera_matrix(index);
  const double W = rig.width - 1.0, H = rig.height - 1.0;
  for (const Eigen::Vector2d& px : {Eigen::Vector2d(0, 0), Eigen::Vector2d(W, 0), Eigen::Vector2d(0, H),
                                    Eigen::Vector2d(W, H), Eigen::Vector2d(W / 2, 0),
                                    Eigen::Vector2d(0, H / 2), Eigen::Vector2d(W, H / 2),
                                    Eigen::Vector2d(W / 2, H)}) {
    const Eigen::Vector2d distorted((px.x() - K(0, 2)) / K(0, 0), (px.y() - K(1, 2)) / K(1, 1));
    const Eigen::Vector2d n = lens.undistort(distorted);
    if (!n.allFinite() || (lens.distort(n) - distorted).norm() > 1e-9 ||
        !lens.one_to_one_up_to(1.05 * n.norm()))
      throw ParamError(std::string(kLensField[index]) + ".distortion",
                       "the lens model folds over inside the image (no single ray per pixel); "
                       "use smaller coefficients or a smaller field of view");
  }
}

}  // namespace

double StereoRig::fx() const { return 0.5 * width / std::tan(0.5 * horizontal_fov); }

bool StereoRig::ideal() const {
  return lenses[0].ideal() && lenses[1].ideal() && right_rotation.isZero(0.0) &&
         right_offset.isZero(0.0);
}

ImageKind StereoRig::images() const {
  const bool distortion = lenses[0].distortion.model != DistortionModel::None ||
                          lenses[1].distortion.model != DistortionModel::None;
  return raw_images || distortion ? ImageKind::Raw : ImageKind::Rectified;
}

Eigen::Matrix3d StereoRig::camera_matrix(int index) const {
  const CameraLens& lens = lenses[static_cast<std::size_t>(index)];
  // Without distortion this is fx() itself, bit for bit.
  const double nominal = lens.distortion.model == DistortionModel::None
                             ? fx()
                             : 0.5 * width / lens.distortion.radial(std::tan(0.5 * horizontal_fov));
  const double f = lens.focal_scale * nominal;
  Eigen::Matrix3d K;
  K << f, 0.0, cx() + lens.principal_offset.x(),  //
      0.0, lens.aspect * f, cy() + lens.principal_offset.y(),  //
      0.0, 0.0, 1.0;
  return K;
}

StereoCamera StereoRig::cameras() const {
  StereoCamera pair;
  pair.images = images();
  if (ideal()) {
    pair.left = CameraInfo::ideal("left", width, height, fx(), cx(), cy(), 0.0);
    pair.right = CameraInfo::ideal("right", width, height, fx(), cx(), cy(), baseline);
    return pair;
  }
  const detail::Rectification rect = detail::rectify(*this);
  pair.left = physical_info(*this, 0, rect);
  pair.right = physical_info(*this, 1, rect);
  return pair;
}

namespace {

/// Camera body <- optical frame of camera `index` of the level rig.
Eigen::Isometry3d level_cambody_optical(const StereoRig& rig, int index) {
  Eigen::Isometry3d T = sim::T_cambody_optical();
  if (index != 1) return T;
  if (rig.right_rotation.isZero(0.0) && rig.right_offset.isZero(0.0)) {
    // The right camera sits one baseline along +x_opt, i.e. along -y_body.
    T.translation() = Eigen::Vector3d(0.0, -rig.baseline, 0.0);
    return T;
  }
  Eigen::Isometry3d T_left_right = Eigen::Isometry3d::Identity();
  const double angle = rig.right_rotation.norm();
  if (angle > 0.0) T_left_right.linear() = Eigen::AngleAxisd(angle, rig.right_rotation / angle).toRotationMatrix();
  T_left_right.translation() = Eigen::Vector3d(rig.baseline, 0.0, 0.0) + rig.right_offset;
  return T * T_left_right;
}

}  // namespace

Eigen::Isometry3d StereoRig::T_cambody_optical(int index) const {
  const Eigen::Isometry3d level = level_cambody_optical(*this, index);
  if (roll == 0.0) return level;
  // Turning the camera anticlockwise about the forward axis (as seen from
  // behind) is a right-handed turn about body x.
  return Eigen::Isometry3d(Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX())) * level;
}

Eigen::Isometry3d StereoRig::T_optical_camera() const {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  if (images() == ImageKind::Raw || ideal()) return T;
  T.linear() = detail::rectifying_rotations(*this)[0].transpose();
  return T;
}

Eigen::Vector2d StereoRig::project(int index, const Eigen::Vector3d& p_cambody) const {
  return project_optical(index, T_cambody_optical(index).inverse() * p_cambody);
}

Eigen::Vector2d StereoRig::project_optical(int index, const Eigen::Vector3d& p) const {
  if (!(p.z() > 0.0)) return {kNaN, kNaN};
  if (ideal() && images() == ImageKind::Rectified) {
    const double f = fx();
    return {f * p.x() / p.z() + cx(), f * p.y() / p.z() + cy()};
  }
  if (images() == ImageKind::Raw) return detail::raw_pixel(*this, index, p);
  // Rectified images of a non-ideal rig (without distortion, so rectify()
  // needs only the image corners), remembered for the next point.
  const detail::Rectification& rect = detail::rectify_cached(*this);
  const Eigen::Vector3d q = rect.R_rect_optical[static_cast<std::size_t>(index)] * p;
  if (!(q.z() > 0.0)) return {kNaN, kNaN};
  const Eigen::Vector3d px = rect.K * (q / q.z());
  return px.head<2>();
}

StereoRig StereoRig::with_real_lenses(DistortionModel model) const {
  StereoRig rig = *this;
  const LensDistortion d = typical_distortion(model, horizontal_fov);
  const double scale = width / 1280.0;  // offsets in pixels grow with the sensor
  rig.lenses[0] = CameraLens{1.0, 1.002, Eigen::Vector2d(6.0, -4.0) * scale, d};
  rig.lenses[1] = CameraLens{1.004, 1.0015, Eigen::Vector2d(-3.5, 5.0) * scale, d};
  rig.right_rotation = Eigen::Vector3d(0.0021, -0.0043, 0.0017);  // ~0.3 deg
  rig.right_offset = Eigen::Vector3d(0.0, 0.0008, -0.0005);
  return rig;
}

void StereoRig::validate() const {
  if (width < 16 || width > 16384) throw ParamError("camera.width", "must be 16..16384 px");
  if (height < 16 || height > 16384) throw ParamError("camera.height", "must be 16..16384 px");
  if (!(horizontal_fov > 0.05 && horizontal_fov < 3.0))
    throw ParamError("camera.horizontal_fov", "must be in (0.05, 3.0) rad");
  if (!(baseline > 0.0 && baseline < 5.0)) throw ParamError("camera.baseline", "must be in (0, 5) m");
  if (!std::isfinite(roll)) throw ParamError("camera.roll", "must be a finite angle [rad]");
  for (int i = 0; i < 2; ++i) lenses[static_cast<std::size_t>(i)].validate(kLensField[i], width, height);
  if (!(right_rotation.allFinite() && right_rotation.norm() <= 0.1))
    throw ParamError("camera.right_rotation", "must be a rotation vector of at most 0.1 rad");
  if (!(right_offset.allFinite() && right_offset.norm() <= 0.5 * baseline))
    throw ParamError("camera.right_offset", "must be at most half the baseline long");
  for (int i = 0; i < 2; ++i) check_lens_covers_image(*this, i);
  if (!ideal()) detail::rectify(*this);  // throws when the pair has no common view
}

}  // namespace l2s::sim
