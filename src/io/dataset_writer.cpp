// Writing a dataset folder that Dataset::open and tools/check_dataset.py accept.
#include <l2s/io/dataset.hpp>

#include <l2s/error.hpp>
#include <l2s/io/camera_yaml.hpp>
#include <l2s/io/dataset_yaml.hpp>
#include <l2s/io/image_io.hpp>
#include <l2s/io/target_yaml.hpp>
#include <l2s/io/transform_yaml.hpp>

#include "io/stereo_check.hpp"

#include <filesystem>

namespace fs = std::filesystem;

namespace l2s::io {
namespace {

std::string join(const std::string& folder, const std::string& name) {
  return (fs::path(folder) / name).string();
}

void check_image(const Image& image, const CameraInfo& camera, const char* field) {
  if (image.width != camera.width || image.height != camera.height)
    throw ParamError(field, "image is " + std::to_string(image.width) + "x" +
                                std::to_string(image.height) + ", the camera " +
                                std::to_string(camera.width) + "x" + std::to_string(camera.height));
}

void check_stem(const std::string& stem) {
  if (stem.empty() || stem[0] == '.' || stem.find_first_of("/\\") != std::string::npos)
    throw ParamError("frame.stem", "'" + stem + "' is not a plain file stem");
}

}  // namespace

DatasetWriter::DatasetWriter(const std::string& folder, const StereoCamera& cameras,
                             const Target& target, CameraLayout layout)
    : folder_(folder), cameras_(cameras), layout_(layout) {
  const bool mono = layout == CameraLayout::Mono;
  // Refuse what the reader would reject, before any file exists.
  if (mono)
    check_single_camera(cameras.left, cameras.images, join(folder, "left.yaml"));
  else
    check_pair(cameras, join(folder, "left.yaml"), join(folder, "right.yaml"));
  target.validate();
  for (const char* sub : {"lidar", "left", "right"}) {
    if (mono && std::string(sub) == "right") continue;
    std::error_code error;
    fs::create_directories(join(folder, sub), error);
    if (error) throw FileError(join(folder, sub), "cannot create folder: " + error.message());
  }
  // Rectified is the default: such folders need no dataset.yaml (and must not
  // keep one from an earlier raw dataset written into the same folder).
  if (cameras.images == ImageKind::Raw) {
    write_dataset_info(join(folder, "dataset.yaml"), {cameras.images});
  } else {
    std::error_code error;
    fs::remove(join(folder, "dataset.yaml"), error);
  }
  write_camera_info(join(folder, "left.yaml"), cameras.left);
  if (mono) {
    std::error_code error;
    fs::remove(join(folder, "right.yaml"), error);
  } else {
    write_camera_info(join(folder, "right.yaml"), cameras.right);
  }
  write_target(join(folder, "target.yaml"), target);
}

void DatasetWriter::write(const Frame& frame, PcdEncoding encoding) const {
  check_stem(frame.stem);
  if (lidar_pair_) {
    write_pcd(join(folder_, "lidar2/" + frame.stem + ".pcd"), frame.lidar2, encoding);
    write_pcd(join(folder_, "lidar/" + frame.stem + ".pcd"), frame.lidar, encoding);
    return;
  }
  check_image(frame.left, cameras_.left, "frame.left");
  const bool mono = layout_ == CameraLayout::Mono;
  if (!mono) check_image(frame.right, cameras_.right, "frame.right");
  // Lidar last: a frame counts once its .pcd exists, and then its images do too.
  write_png(join(folder_, "left/" + frame.stem + ".png"), frame.left);
  if (!mono) write_png(join(folder_, "right/" + frame.stem + ".png"), frame.right);
  write_pcd(join(folder_, "lidar/" + frame.stem + ".pcd"), frame.lidar, encoding);
}

void DatasetWriter::write_images(const Frame& frame) const {
  check_stem(frame.stem);
  if (lidar_pair_) throw ParamError("frame", "a lidar-lidar dataset has no images");
  const bool mono = layout_ == CameraLayout::Mono;
  check_image(frame.left, cameras_.left, "frame.left");
  if (!mono) check_image(frame.right, cameras_.right, "frame.right");
  write_png(join(folder_, "left/" + frame.stem + ".png"), frame.left);
  if (!mono) write_png(join(folder_, "right/" + frame.stem + ".png"), frame.right);
}

void DatasetWriter::write_accumulated_lidar(const std::string& stem, const LidarCloud& cloud,
                                            PcdEncoding encoding) const {
  check_stem(stem);
  if (lidar_pair_) throw ParamError("lidar", "a lidar-lidar dataset pairs sweeps by stem, not accumulated clouds");
  write_dataset_info(join(folder_, "dataset.yaml"), {cameras_.images, LidarForm::Accumulated});
  write_pcd(join(folder_, "lidar/" + stem + ".pcd"), cloud, encoding);
}

DatasetWriter DatasetWriter::lidar_pair(const std::string& folder, const Target& target) {
  target.validate();
  for (const char* sub : {"lidar", "lidar2"}) {
    std::error_code error;
    fs::create_directories(join(folder, sub), error);
    if (error) throw FileError(join(folder, sub), "cannot create folder: " + error.message());
  }
  write_target(join(folder, "target.yaml"), target);
  DatasetWriter writer;
  writer.folder_ = folder;
  writer.lidar_pair_ = true;
  return writer;
}

void DatasetWriter::write_ground_truth_lidar2(const Eigen::Isometry3d& T_lidar_lidar2) const {
  write_transform(join(folder_, "ground_truth.yaml"), T_lidar_lidar2, "T_lidar_lidar2");
}

void DatasetWriter::write_ground_truth(const Eigen::Isometry3d& T_lidar_camera) const {
  write_transform(join(folder_, "ground_truth.yaml"), T_lidar_camera);
}

}  // namespace l2s::io
