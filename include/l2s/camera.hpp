#pragma once
// Rectified pinhole cameras as ROS camera_info describes them.

#include <l2s/export.hpp>

#include <Eigen/Core>
#include <string>
#include <vector>

namespace l2s {

/// One camera of a rectified stereo pair, with every field of a ROS
/// camera_info YAML so that a file read and written again keeps its content.
/// Images are rectified: the projection matrix P is the model that counts.
struct L2S_EXPORT CameraInfo {
  std::string camera_name;
  int width = 0;   ///< [px]
  int height = 0;  ///< [px]
  Eigen::Matrix3d camera_matrix = Eigen::Matrix3d::Identity();
  std::string distortion_model = "plumb_bob";
  std::vector<double> distortion_coefficients;
  Eigen::Matrix3d rectification_matrix = Eigen::Matrix3d::Identity();
  Eigen::Matrix<double, 3, 4> projection_matrix = Eigen::Matrix<double, 3, 4>::Identity();

  double fx() const { return projection_matrix(0, 0); }  ///< [px]
  double fy() const { return projection_matrix(1, 1); }  ///< [px]
  double cx() const { return projection_matrix(0, 2); }  ///< [px]
  double cy() const { return projection_matrix(1, 2); }  ///< [px]

  /// Pixel of a point given in the *left* optical frame (P carries the
  /// baseline term, so the right camera's P projects left-frame points).
  /// Returns NaN when the point is not in front of the camera.
  Eigen::Vector2d project(const Eigen::Vector3d& p_left_optical) const;

  /// Builds an ideal rectified camera: square pixels, principal point
  /// (cx, cy), and P[0][3] = -fx * baseline (0 for the left camera).
  static CameraInfo ideal(const std::string& name, int width, int height, double fx, double cx,
                          double cy, double baseline_m = 0.0);
};

/// Which images a camera delivers (DATASET.md, dataset.yaml `images:`).
enum class ImageKind {
  Rectified,  ///< already rectified: P is the model; the camera frame is the rectified frame
  Raw,        ///< as the driver publishes them: K and D apply, R and P rectify; the camera frame is K's
};

/// A stereo pair; the left camera's optical frame is "the camera frame". With
/// raw images that is the physical left camera of K and D, not the rectified
/// frame (p_rect = R_left * p_camera).
struct StereoCamera {
  CameraInfo left;
  CameraInfo right;
  ImageKind images = ImageKind::Rectified;  ///< what the image folders hold

  /// [m] B = -P_right[0][3] / fx_right (DATASET.md).
  double baseline() const { return -right.projection_matrix(0, 3) / right.fx(); }
};

}  // namespace l2s
