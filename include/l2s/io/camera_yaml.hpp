#pragma once
// ROS camera_info YAML files (left.yaml, right.yaml), as written by the ROS
// camera_calibration tool.

#include <l2s/camera.hpp>

#include <string>

namespace l2s::io {

/// Reads a camera_info YAML; throws FileError naming the file and the
/// missing or malformed key (wrong matrix size, non-numeric data, ...).
/// Required: image_width, image_height (positive integers) and a 3x4
/// projection_matrix with fx, fy > 0. Optional: camera_name, distortion_model,
/// distortion_coefficients (any length, also 0), rectification_matrix
/// (default identity) and camera_matrix (default: the left 3x3 block of P).
CameraInfo read_camera_info(const std::string& path);

/// Writes a camera_info YAML atomically.
void write_camera_info(const std::string& path, const CameraInfo& camera);

/// Reads left.yaml and right.yaml of a dataset folder and checks the pair for
/// what `images` needs. Both kinds: same image size; P a rectified pair (fx, fy,
/// cy equal within 1e-3 px; left |P[0][3]| below 1e-3 * fx; baseline
/// -P_right[0][3] / fx_right > 0). Raw images also need, per camera: K with
/// fx, fy > 0, last row 0 0 1 and the principal point inside the image; D of a
/// length its model takes (plumb_bob 4, 5 or 8; equidistant 4; other models
/// are errors); R a rotation. The FileError names the file and key that break
/// the rule. The result's `images` is `images`.
StereoCamera read_stereo_camera(const std::string& left_path, const std::string& right_path,
                                ImageKind images = ImageKind::Rectified);

}  // namespace l2s::io
