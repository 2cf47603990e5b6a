// ROS camera_info YAML. Lenient where real files differ (camera_name,
// camera_matrix, rectification_matrix and the distortion vector may be absent;
// the distortion vector may have any length), strict where the calibrator
// depends on the content: image size and the 3x4 projection matrix.
#include <l2s/io/camera_yaml.hpp>

#include <l2s/error.hpp>

#include "detail/atomic_file.hpp"
#include "io/stereo_check.hpp"
#include "io/yaml_helpers.hpp"


namespace l2s::io {

CameraInfo read_camera_info(const std::string& path) {
  const YAML::Node root = yaml::load_file(path);
  if (!root.IsMap()) throw FileError(path, "expected a camera_info map (image_width, ...)");

  CameraInfo camera;
  camera.width = yaml::read_positive_int(root, "image_width", path);
  camera.height = yaml::read_positive_int(root, "image_height", path);
  if (yaml::has_key(root, "camera_name") && !root["camera_name"].IsNull())
    camera.camera_name = yaml::read_string(root, "camera_name", path);
  camera.projection_matrix = yaml::read_matrix(root, "projection_matrix", path, 3, 4);

  // Rectified images need only P; K defaults to P's left block when absent.
  camera.camera_matrix = yaml::has_key(root, "camera_matrix")
                             ? Eigen::Matrix3d(yaml::read_matrix(root, "camera_matrix", path, 3, 3))
                             : Eigen::Matrix3d(camera.projection_matrix.leftCols<3>());
  if (yaml::has_key(root, "rectification_matrix"))
    camera.rectification_matrix = yaml::read_matrix(root, "rectification_matrix", path, 3, 3);
  if (yaml::has_key(root, "distortion_model"))
    camera.distortion_model = yaml::read_string(root, "distortion_model", path);
  if (yaml::has_key(root, "distortion_coefficients"))
    camera.distortion_coefficients = yaml::read_vector(root, "distortion_coefficients", path);
  else
    camera.distortion_coefficients.clear();

  if (!(camera.fx() > 0.0) || !(camera.fy() > 0.0))
    throw FileError(path, "projection_matrix: fx and fy must be positive");
  return camera;
}

void write_camera_info(const std::string& path, const CameraInfo& camera) {
  YAML::Emitter out;
  out << YAML::BeginMap;
  out << YAML::Key << "image_width" << YAML::Value << camera.width;
  out << YAML::Key << "image_height" << YAML::Value << camera.height;
  out << YAML::Key << "camera_name" << YAML::Value << camera.camera_name;
  yaml::emit_matrix(out, "camera_matrix", camera.camera_matrix);
  out << YAML::Key << "distortion_model" << YAML::Value << camera.distortion_model;
  const auto& d = camera.distortion_coefficients;
  yaml::emit_matrix(
      out, "distortion_coefficients",
      Eigen::Map<const Eigen::MatrixXd>(d.data(), 1, static_cast<Eigen::Index>(d.size())));
  yaml::emit_matrix(out, "rectification_matrix", camera.rectification_matrix);
  yaml::emit_matrix(out, "projection_matrix", camera.projection_matrix);
  out << YAML::EndMap;
  if (!out.good()) throw FileError(path, std::string("cannot emit YAML: ") + out.GetLastError());
  detail::write_file_atomically(path, yaml::document_text(out));
}

StereoCamera read_stereo_camera(const std::string& left_path, const std::string& right_path,
                                ImageKind images) {
  StereoCamera cameras;
  cameras.left = read_camera_info(left_path);
  cameras.right = read_camera_info(right_path);
  cameras.images = images;
  check_pair(cameras, left_path, right_path);
  return cameras;
}

}  // namespace l2s::io
