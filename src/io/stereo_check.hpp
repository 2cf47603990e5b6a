#pragma once
// The rectified-pair check shared by the camera reader and the dataset writer,
// so that the writer never produces a folder the reader rejects.

#include <l2s/camera.hpp>

#include <string>

namespace l2s::io {

/// Throws FileError naming the offending file unless the pair is rectified:
/// same image size, fx, fy and cy; left P[0][3] ~ 0; baseline > 0.
void check_rectified_pair(const StereoCamera& cameras, const std::string& left_path,
                          const std::string& right_path);

}  // namespace l2s::io
