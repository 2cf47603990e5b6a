#pragma once
// dataset.yaml: what kind of images a dataset folder holds, and how its lidar
// files relate to its image frames (DATASET.md, version 3).

#include <l2s/camera.hpp>
#include <l2s/export.hpp>

#include <string>

namespace l2s::io {

/// The content of dataset.yaml. Absent file or key: the defaults below.
/// How a dataset's lidar files pair with its image frames.
enum class LidarForm {
  Sweeps,       ///< one sweep per frame, matched by stem (`lidar: sweeps`, the default)
  Accumulated,  ///< one cloud per static board pose, integrated over time; it pairs with every image
                ///< frame from its stem up to the next lidar file's (`lidar: accumulated`)
};

struct DatasetInfo {
  ImageKind images = ImageKind::Rectified;  ///< `images: rectified` (default) or `images: raw`
  LidarForm lidar = LidarForm::Sweeps;      ///< `lidar: sweeps` (default) or `lidar: accumulated`
};

/// Reads dataset.yaml. An empty file means the defaults. Throws FileError naming
/// the file and the key for malformed YAML, an unknown key (a typo must not be
/// ignored), an images value other than rectified/raw or a lidar value other
/// than sweeps/accumulated.
L2S_EXPORT DatasetInfo read_dataset_info(const std::string& path);

/// Reads dataset.yaml when the file exists, otherwise returns the defaults.
L2S_EXPORT DatasetInfo read_dataset_info_or_default(const std::string& path);

/// Writes dataset.yaml atomically.
L2S_EXPORT void write_dataset_info(const std::string& path, const DatasetInfo& info);

/// "rectified" or "raw", as dataset.yaml spells it.
L2S_EXPORT std::string to_string(ImageKind images);
/// "sweeps" or "accumulated", as dataset.yaml spells it.
L2S_EXPORT std::string to_string(LidarForm lidar);

}  // namespace l2s::io
