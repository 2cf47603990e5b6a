// dataset.yaml: strict on keys and values, because a misspelt `images: raw`
// silently read as rectified would bias every result made from the folder.
#include <l2s/io/dataset_yaml.hpp>

#include <l2s/error.hpp>

#include "detail/atomic_file.hpp"
#include "io/yaml_helpers.hpp"

#include <filesystem>

namespace l2s::io {

std::string to_string(ImageKind images) { return images == ImageKind::Raw ? "raw" : "rectified"; }
std::string to_string(LidarForm lidar) { return lidar == LidarForm::Accumulated ? "accumulated" : "sweeps"; }

DatasetInfo read_dataset_info(const std::string& path) {
  const YAML::Node root = yaml::load_file(path);
  DatasetInfo info;
  if (root.IsNull()) return info;  // an empty file: all defaults
  if (!root.IsMap())
    throw FileError(path, "expected a map of keys (images: rectified|raw, lidar: sweeps|accumulated)");
  for (const auto& entry : root) {
    if (!entry.first.IsScalar()) throw FileError(path, "keys must be plain words (images, lidar)");
    const std::string key = entry.first.Scalar();
    if (key != "images" && key != "lidar") throw FileError(path, "unknown key '" + key + "' (known: images, lidar)");
  }
  if (yaml::has_key(root, "images")) {
    const std::string value = yaml::read_string(root, "images", path);
    if (value == "raw")
      info.images = ImageKind::Raw;
    else if (value != "rectified")
      throw FileError(path, "images: '" + value + "' is neither rectified nor raw");
  }
  if (yaml::has_key(root, "lidar")) {
    const std::string value = yaml::read_string(root, "lidar", path);
    if (value == "accumulated")
      info.lidar = LidarForm::Accumulated;
    else if (value != "sweeps")
      throw FileError(path, "lidar: '" + value + "' is neither sweeps nor accumulated");
  }
  return info;
}

DatasetInfo read_dataset_info_or_default(const std::string& path) {
  std::error_code error;
  if (!std::filesystem::exists(path, error)) return {};
  return read_dataset_info(path);
}

void write_dataset_info(const std::string& path, const DatasetInfo& info) {
  YAML::Emitter out;
  out << YAML::BeginMap;
  out << YAML::Key << "images" << YAML::Value << to_string(info.images);
  // Written only when it differs from the default, so sweep datasets stay
  // readable by version 2 readers.
  if (info.lidar != LidarForm::Sweeps) out << YAML::Key << "lidar" << YAML::Value << to_string(info.lidar);
  out << YAML::EndMap;
  if (!out.good()) throw FileError(path, std::string("cannot emit YAML: ") + out.GetLastError());
  detail::write_file_atomically(path, yaml::document_text(out));
}

}  // namespace l2s::io
