// Reading a dataset folder (DATASET.md): the YAML files at open, frames on demand.
#include <l2s/io/dataset.hpp>

#include <l2s/error.hpp>
#include <l2s/io/camera_yaml.hpp>
#include <l2s/io/dataset_yaml.hpp>
#include <l2s/io/image_io.hpp>
#include <l2s/io/ring_recovery.hpp>
#include <l2s/io/target_yaml.hpp>
#include <l2s/io/transform_yaml.hpp>

#include "io/stereo_check.hpp"

#include <algorithm>
#include <filesystem>
#include <set>

namespace fs = std::filesystem;

namespace l2s::io {
namespace {

constexpr std::size_t kStemsListed = 5;  // enough to see the pattern, short enough to read

std::string join(const std::string& folder, const std::string& name) {
  return (fs::path(folder) / name).string();
}

// Stems of the regular files `sub/*ext`; hidden and temporary files are not frames.
std::set<std::string> stems_in(const std::string& folder, const std::string& sub,
                               const std::string& ext) {
  const std::string directory = join(folder, sub);
  std::error_code error;
  if (!fs::is_directory(directory, error)) throw FileError(directory, "missing folder");
  std::set<std::string> stems;
  for (const auto& entry : fs::directory_iterator(directory, error)) {
    const fs::path& p = entry.path();
    if (p.extension() != ext || p.filename().string()[0] == '.') continue;
    if (entry.is_regular_file(error)) stems.insert(p.stem().string());
  }
  if (error) throw FileError(directory, "cannot list folder: " + error.message());
  return stems;
}

// "000003 (no left/000003.png), ..." for stems missing from some of the folders.
std::string describe_mismatch(const std::set<std::string>& lidar, const std::set<std::string>& left,
                              const std::set<std::string>& right) {
  std::set<std::string> all = lidar;
  all.insert(left.begin(), left.end());
  all.insert(right.begin(), right.end());
  std::string text;
  std::size_t listed = 0, mismatched = 0;
  for (const std::string& stem : all) {
    std::string missing;
    if (!lidar.count(stem)) missing += " lidar/" + stem + ".pcd";
    if (!left.count(stem)) missing += " left/" + stem + ".png";
    if (!right.count(stem)) missing += " right/" + stem + ".png";
    if (missing.empty()) continue;
    if (listed++ < kStemsListed) text += (text.empty() ? "" : ", ") + stem + " (no" + missing + ")";
    ++mismatched;
  }
  if (mismatched > kStemsListed)
    text += ", and " + std::to_string(mismatched - kStemsListed) + " more";
  return text;
}

// A lidar-lidar dataset's stems: lidar/ and lidar2/ must list the same.
std::set<std::string> lidar_pair_stems(const std::string& folder) {
  const auto lidar = stems_in(folder, "lidar", ".pcd");
  const auto lidar2 = stems_in(folder, "lidar2", ".pcd");
  if (lidar != lidar2) {
    std::string text;
    std::size_t listed = 0, mismatched = 0;
    std::set<std::string> all = lidar;
    all.insert(lidar2.begin(), lidar2.end());
    for (const std::string& stem : all) {
      const char* missing = !lidar.count(stem) ? " (no lidar/" : !lidar2.count(stem) ? " (no lidar2/" : nullptr;
      if (!missing) continue;
      if (listed++ < kStemsListed) text += (text.empty() ? "" : ", ") + stem + missing + stem + ".pcd)";
      ++mismatched;
    }
    if (mismatched > kStemsListed) text += ", and " + std::to_string(mismatched - kStemsListed) + " more";
    throw FileError(join(folder, "lidar2"), "frame stems differ from lidar/: " + text);
  }
  if (lidar.empty()) throw FileError(folder, "no frames (lidar/*.pcd, lidar2/*.pcd)");
  return lidar;
}

void load_sweep(const std::string& path, LidarCloud* cloud, RingSource* source,
                std::optional<RingRecoveryReport>* recovery) {
  PcdFile sweep = read_pcd_file(path);
  *cloud = std::move(sweep.cloud);
  SweptRings rings = settle_rings(*cloud, sweep.height);
  *source = rings.source;
  *recovery = std::move(rings.recovery);
}

void check_size(const Image& image, const CameraInfo& camera, const std::string& image_path,
                const std::string& yaml_name) {
  if (image.width == camera.width && image.height == camera.height) return;
  throw FileError(image_path, "image is " + std::to_string(image.width) + "x" +
                                  std::to_string(image.height) + " but " + yaml_name + " says " +
                                  std::to_string(camera.width) + "x" +
                                  std::to_string(camera.height));
}

/// `lidar: accumulated` (DATASET.md v3): the frames are the image frames;
/// each lidar file covers those from its stem up to the next lidar file's.
void pair_accumulated(const std::string& folder, const std::set<std::string>& lidar,
                      const std::set<std::string>& left, const std::set<std::string>& right,
                      std::vector<std::string>& stems, std::vector<std::string>& lidar_of_frame) {
  if (left != right) {
    std::set<std::string> images = left;  // no lidar file is missing: they pair by position
    images.insert(right.begin(), right.end());
    throw FileError(folder, "frame stems differ between left/ and right/: " + describe_mismatch(images, left, right));
  }
  if (left.empty()) throw FileError(folder, "no image frames (left/*.png)");
  if (lidar.empty()) throw FileError(join(folder, "lidar"), "no lidar files (*.pcd)");
  for (const std::string& stem : lidar)
    if (!left.count(stem))
      throw FileError(join(folder, "lidar/" + stem + ".pcd"),
                      "no image frame " + stem + " (lidar: accumulated pairs a lidar file with the image frames "
                      "from its own stem on)");
  stems.assign(left.begin(), left.end());
  std::string covering;
  for (const std::string& stem : stems) {
    if (lidar.count(stem)) covering = stem;
    lidar_of_frame.push_back(covering);
  }
}

/// Stereo or mono (DATASET.md v2): right.yaml and right/ come together or not at all.
CameraLayout camera_layout(const std::string& folder) {
  std::error_code error;
  const std::string right_yaml = join(folder, "right.yaml"), right_dir = join(folder, "right");
  const bool has_yaml = fs::exists(right_yaml, error), has_dir = fs::is_directory(right_dir, error);
  if (has_yaml && !has_dir) throw FileError(right_dir, "missing folder (right.yaml is there: a stereo dataset)");
  if (has_dir && !has_yaml) throw FileError(right_yaml, "missing file (right/ is there: a stereo dataset)");
  return has_yaml ? CameraLayout::Stereo : CameraLayout::Mono;
}

}  // namespace

Dataset Dataset::open(const std::string& folder) {
  std::error_code error;
  if (!fs::is_directory(folder, error)) throw FileError(folder, "no such dataset folder");
  Dataset dataset;
  dataset.folder_ = folder;
  const std::string info_path = join(folder, "dataset.yaml");
  dataset.has_dataset_file_ = fs::exists(info_path, error);
  const DatasetInfo info = read_dataset_info_or_default(info_path);
  const std::string target_path = join(folder, "target.yaml");
  dataset.has_target_file_ = fs::exists(target_path, error);
  dataset.target_ = read_target_or_default(target_path);
  dataset.lidar_form_ = info.lidar;
  dataset.has_lidar2_ = fs::is_directory(join(folder, "lidar2"), error);
  if (dataset.has_lidar2_) {  // lidar-lidar: no cameras to read
    if (dataset.accumulated())
      throw FileError(info_path, "lidar: accumulated pairs lidar files with image frames; a lidar-lidar dataset "
                                 "(lidar2/) pairs sweeps by stem");
    const auto stems = lidar_pair_stems(folder);
    dataset.stems_.assign(stems.begin(), stems.end());
    dataset.lidar_stems_ = dataset.lidar_of_frame_ = dataset.stems_;
    return dataset;
  }
  const std::string left_yaml = join(folder, "left.yaml"), right_yaml = join(folder, "right.yaml");
  dataset.layout_ = camera_layout(folder);
  if (dataset.mono()) {
    dataset.cameras_.left = read_camera_info(left_yaml);
    dataset.cameras_.images = info.images;
    check_single_camera(dataset.cameras_.left, info.images, left_yaml);
    dataset.warnings_ = rectified_camera_warnings(dataset.cameras_.left, info.images, left_yaml);
  } else {
    dataset.cameras_ = read_stereo_camera(left_yaml, right_yaml, info.images);
    dataset.warnings_ = rectified_pair_warnings(dataset.cameras_, left_yaml, right_yaml);
  }

  const auto lidar = stems_in(folder, "lidar", ".pcd");
  const auto left = stems_in(folder, "left", ".png");
  const auto right = dataset.mono() ? left : stems_in(folder, "right", ".png");
  dataset.lidar_stems_.assign(lidar.begin(), lidar.end());  // std::set: already sorted
  if (dataset.accumulated()) {
    pair_accumulated(folder, lidar, left, right, dataset.stems_, dataset.lidar_of_frame_);
    return dataset;
  }
  if (lidar != left || lidar != right)
    throw FileError(folder, "frame stems differ between lidar/, left/ and right/: " +
                                describe_mismatch(lidar, left, right));
  if (lidar.empty()) throw FileError(folder, "no frames (lidar/*.pcd, left/*.png, right/*.png)");
  dataset.stems_ = dataset.lidar_of_frame_ = dataset.lidar_stems_;
  return dataset;
}

const std::string& Dataset::lidar_stem(std::size_t index) const {
  if (index >= lidar_of_frame_.size())
    throw ParamError("index", std::to_string(index) + " is past the last of " + std::to_string(stems_.size()) +
                                  " frames in " + folder_);
  return lidar_of_frame_[index];
}

Frame Dataset::load(std::size_t index) const {
  Frame frame = load_images(index);
  if (!frame.lidar_stem.empty())
    load_sweep(lidar_path(frame.lidar_stem), &frame.lidar, &frame.ring_source, &frame.ring_recovery);
  if (has_lidar2_) load_sweep(lidar2_path(frame.stem), &frame.lidar2, &frame.lidar2_ring_source,
                              &frame.lidar2_ring_recovery);
  return frame;
}

Frame Dataset::load_images(std::size_t index) const {
  Frame frame;
  frame.lidar_stem = lidar_stem(index);
  frame.stem = stems_[index];
  if (has_lidar2_) return frame;  // lidar-lidar: no images
  frame.left = read_image(left_path(frame.stem));
  check_size(frame.left, cameras_.left, left_path(frame.stem), "left.yaml");
  if (!mono()) {
    // Both YAMLs share one size (read_stereo_camera), so left and right match too.
    frame.right = read_image(right_path(frame.stem));
    check_size(frame.right, cameras_.right, right_path(frame.stem), "right.yaml");
  }
  return frame;
}

std::optional<Eigen::Isometry3d> Dataset::ground_truth() const {
  const std::string path = join(folder_, "ground_truth.yaml");
  std::error_code error;
  if (!fs::exists(path, error)) return std::nullopt;
  return read_transform(path, has_lidar2_ ? "T_lidar_lidar2" : "T_lidar_camera");
}

std::string Dataset::lidar_path(const std::string& stem) const {
  return join(folder_, "lidar/" + stem + ".pcd");
}
std::string Dataset::left_path(const std::string& stem) const {
  return join(folder_, "left/" + stem + ".png");
}
std::string Dataset::right_path(const std::string& stem) const {
  return join(folder_, "right/" + stem + ".png");
}
std::string Dataset::lidar2_path(const std::string& stem) const {
  return join(folder_, "lidar2/" + stem + ".pcd");
}

}  // namespace l2s::io
