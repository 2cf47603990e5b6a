#pragma once
// dataset.yaml: what kind of images a dataset folder holds (DATASET.md, version 2).

#include <l2s/camera.hpp>

#include <string>

namespace l2s::io {

/// The content of dataset.yaml. Absent file or key: the defaults below.
struct DatasetInfo {
  ImageKind images = ImageKind::Rectified;  ///< `images: rectified` (default) or `images: raw`
};

/// Reads dataset.yaml. An empty file means the defaults. Throws FileError naming
/// the file and the key for malformed YAML, an unknown key (a typo must not be
/// ignored) or a value other than rectified/raw.
DatasetInfo read_dataset_info(const std::string& path);

/// Reads dataset.yaml when the file exists, otherwise returns the defaults.
DatasetInfo read_dataset_info_or_default(const std::string& path);

/// Writes dataset.yaml atomically.
void write_dataset_info(const std::string& path, const DatasetInfo& info);

/// "rectified" or "raw", as dataset.yaml spells it.
std::string to_string(ImageKind images);

}  // namespace l2s::io
