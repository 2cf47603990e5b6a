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

namespace {

/// Whether `key` holds `other` rather than `usual` (its value when absent);
/// any third value is an error naming both.
bool reads_other(const YAML::Node& root, const char* key, const char* usual, const char* other,
                 const std::string& path) {
  if (!yaml::has_key(root, key)) return false;
  const std::string value = yaml::read_string(root, key, path);
  if (value != usual && value != other)
    throw FileError(path, std::string(key) + ": '" + value + "' is neither " + usual + " nor " + other);
  return value == other;
}

}  // namespace

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
  if (reads_other(root, "images", "rectified", "raw", path)) info.images = ImageKind::Raw;
  if (reads_other(root, "lidar", "sweeps", "accumulated", path)) info.lidar = LidarForm::Accumulated;
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
