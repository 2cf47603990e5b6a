#pragma once
// Transform files: ground_truth.yaml and calibration results share the key
// T_lidar_camera (a 4x4 matrix with rows/cols/data).

#include <l2s/export.hpp>

#include <Eigen/Geometry>

#include <string>

namespace l2s::io {

/// Reads the 4x4 matrix stored under `key` (other keys are ignored); throws
/// FileError when the file or key is missing, the matrix is not 4x4, its last
/// row is not 0 0 0 1, or its rotation is a reflection or off by more than 1e-3
/// (max |R^T R - I|). A rotation orthonormal within 1e-9 is returned bit for bit;
/// one within 1e-3 (printed with few decimals) is projected onto the nearest rotation.
L2S_EXPORT Eigen::Isometry3d read_transform(const std::string& path,
                                 const std::string& key = "T_lidar_camera");

/// The DATASET.md key `path` holds: T_lidar_camera, else T_lidar_lidar2
/// (a lidar-lidar dataset or result); FileError when it holds neither.
L2S_EXPORT std::string transform_key(const std::string& path);

/// Writes a file holding only `key`, atomically, in the shortest decimal form
/// that reads back exactly; for T_lidar_camera with the frame comment of DATASET.md.
L2S_EXPORT void write_transform(const std::string& path, const Eigen::Isometry3d& T,
                     const std::string& key = "T_lidar_camera");

}  // namespace l2s::io
