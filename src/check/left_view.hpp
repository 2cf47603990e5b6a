#pragma once
// Projection of camera-frame points into the rectified left image, with a
// lidar-to-camera transform folded in (private to the library).

#include <l2s/camera.hpp>

#include <Eigen/Geometry>

namespace l2s::detail {

/// The rectified left image as the check sees it: p_rect = R * p_camera for
/// raw images (R = the left rectification), p_rect = p_camera otherwise; then P.
struct LeftView {
  Eigen::Matrix3d R_rect_camera = Eigen::Matrix3d::Identity();
  Eigen::Matrix<double, 3, 4> P = Eigen::Matrix<double, 3, 4>::Zero();
  int width = 0;    ///< [px]
  int height = 0;   ///< [px]
  double fx = 1.0;  ///< [px]
  double fx_baseline = 0.0;  ///< [px m] of the rectified pair: depth z matches at disparity fx_baseline / z

  static LeftView of(const StereoCamera& cameras) {
    LeftView view;
    if (cameras.images == ImageKind::Raw) view.R_rect_camera = cameras.left.rectification_matrix;
    view.P = cameras.left.projection_matrix;
    view.width = cameras.left.width;
    view.height = cameras.left.height;
    view.fx = cameras.left.fx();
    view.fx_baseline = -cameras.right.projection_matrix(0, 3);
    return view;
  }
};

/// Lidar points to rectified pixels for one transform: uvw = M p + m.
class LidarProjector {
 public:
  LidarProjector(const LeftView& view, const Eigen::Isometry3d& T_camera_lidar)
      : view_(view) {
    const Eigen::Matrix3d PR = view.P.leftCols<3>() * view.R_rect_camera;
    M_ = PR * T_camera_lidar.linear();
    m_ = PR * T_camera_lidar.translation() + view.P.col(3);
    depth_row_ = (view.R_rect_camera * T_camera_lidar.linear()).row(2);
    depth_offset_ = (view.R_rect_camera * T_camera_lidar.translation()).z();
  }
  /// Pixel of a lidar point, false when it is behind (or within 10 cm of) the camera.
  bool project(const Eigen::Vector3d& p_lidar, double& u, double& v) const {
    const Eigen::Vector3d uvw = M_ * p_lidar + m_;
    if (!(uvw.z() > 0.1)) return false;
    u = uvw.x() / uvw.z();
    v = uvw.y() / uvw.z();
    return true;
  }
  /// [m] depth in the rectified frame (what stereo measures).
  double depth(const Eigen::Vector3d& p_lidar) const { return depth_row_.dot(p_lidar) + depth_offset_; }
  bool inside(double u, double v) const {
    return u >= -0.5 && v >= -0.5 && u < view_.width - 0.5 && v < view_.height - 0.5;
  }

 private:
  const LeftView& view_;
  Eigen::Matrix3d M_;
  Eigen::Vector3d m_;
  Eigen::RowVector3d depth_row_;
  double depth_offset_ = 0.0;
};

}  // namespace l2s::detail
