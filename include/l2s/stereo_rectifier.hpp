#pragma once
// Rectifying raw images, as ROS camera_info describes a camera: K and D belong
// to the raw image, R rotates the raw camera's frame into the rectified frame
// and P projects into the rectified image (DATASET.md, "images: raw"). The
// stages that need rectified images (stereo matching) then take raw ones, and
// a result found in the rectified frame converts back to the camera's own:
//   T_lidar_camera = T_lidar_rect * T_rect_camera.

#include <l2s/camera.hpp>
#include <l2s/export.hpp>
#include <l2s/types.hpp>

#include <Eigen/Geometry>

#include <memory>
#include <string>

namespace l2s {

/// One camera: its raw images into the rectified image of its P. For a mono
/// camera (R the identity, P its new camera matrix) that is undistortion.
/// The remap tables are built once at construction; rectify() is a bilinear
/// lookup per pixel.
/// Thread safety: holds only what it was built with; its const functions may
/// run concurrently on one instance, and each call is deterministic (random
/// draws are seeded per call from the params).
class L2S_EXPORT CameraRectifier {
 public:
  /// Throws ParamError naming `name` and the field: a distortion model other
  /// than plumb_bob (4, 5 or 8 coefficients) or equidistant (4), a size or
  /// focal length that is not positive, R that is not a rotation.
  explicit CameraRectifier(const CameraInfo& raw, const std::string& name = "camera");
  ~CameraRectifier();
  CameraRectifier(CameraRectifier&&) noexcept;
  CameraRectifier& operator=(CameraRectifier&&) noexcept;

  /// The rectified image (same size and channels as the raw one); pixels that
  /// see nothing of the raw image are 0. Throws InputError naming the image
  /// ("left image") when it is empty, not 1 or 3 channels, or its size
  /// differs from the camera's.
  Image rectify(const Image& raw) const;

  /// [px] Where a raw pixel lands in the rectified image (undistorted to
  /// convergence, not only the few iterations of a default undistortion).
  Eigen::Vector2d rectify_point(const Eigen::Vector2d& raw_px) const;

  /// The camera of the rectified images: K = P's left 3x3 block, no
  /// distortion, R the identity, P unchanged.
  const CameraInfo& rectified() const { return rectified_; }

  /// p_rect = R_rect_camera * p_camera (the camera_info's R).
  const Eigen::Matrix3d& R_rect_camera() const { return R_rect_camera_; }

 private:
  struct Maps;
  std::unique_ptr<Maps> maps_;
  CameraInfo raw_;
  CameraInfo rectified_;
  Eigen::Matrix3d R_rect_camera_;
  std::string name_;
};

/// A rectified stereo pair of images.
struct RectifiedPair {
  Image left;
  Image right;
};

/// A raw stereo pair into the rectified images of its P's.
/// Thread safety: as CameraRectifier.
class L2S_EXPORT StereoRectifier {
 public:
  /// Throws ParamError as CameraRectifier does (naming "left" or "right"),
  /// and when the two cameras' image sizes differ.
  explicit StereoRectifier(const StereoCamera& raw);

  /// Throws InputError naming the image that cannot be used (as CameraRectifier::rectify).
  RectifiedPair rectify(const Image& left, const Image& right) const;

  /// The rectified pair: ideal cameras of the P's, images = Rectified. The
  /// baseline is the raw pair's (-P_right[0][3] / fx).
  const StereoCamera& rectified() const { return rectified_; }

  /// p_rect = R_rect_camera * p_camera: the left camera's R. The rectified
  /// frame of the pair is the left rectified camera's.
  const Eigen::Matrix3d& R_rect_camera() const { return left_.R_rect_camera(); }

  /// The same as a transform (no translation: the left camera's centre stays).
  Eigen::Isometry3d T_rect_camera() const;

  const CameraRectifier& left() const { return left_; }
  const CameraRectifier& right() const { return right_; }

 private:
  CameraRectifier left_;
  CameraRectifier right_;
  StereoCamera rectified_;
};

}  // namespace l2s
