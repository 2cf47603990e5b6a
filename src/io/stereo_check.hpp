#pragma once
// The checks a stereo pair must pass before the calibrator uses it, shared by
// the camera reader and the dataset writer so that the writer never produces a
// folder the reader rejects. Which checks apply depends on the image kind.

#include <l2s/camera.hpp>

#include <string>
#include <vector>

namespace l2s::io {

/// Throws FileError naming the offending file unless the pair is rectified:
/// same image size, fx, fy and cy; left P[0][3] ~ 0; baseline > 0.
void check_rectified_pair(const StereoCamera& cameras, const std::string& left_path,
                          const std::string& right_path);

/// Throws FileError naming the offending file and key unless a raw pair can be
/// rectified: same image size; each K with positive focal lengths, last row
/// 0 0 1 and its principal point inside the image; D as long as its model needs
/// (plumb_bob 4, 5 or 8; equidistant 4; other models are errors); R a rotation;
/// and P a rectified pair (check_rectified_pair's rules).
void check_raw_pair(const StereoCamera& cameras, const std::string& left_path,
                    const std::string& right_path);

/// check_rectified_pair or check_raw_pair, as cameras.images says.
void check_pair(const StereoCamera& cameras, const std::string& left_path,
                const std::string& right_path);

/// The one camera of a mono dataset: for raw images K, D and R as
/// check_raw_pair checks each camera; for both kinds P[0][3] ~ 0 (the
/// reference camera). Throws FileError naming `path` and the key.
void check_single_camera(const CameraInfo& camera, ImageKind images, const std::string& path);

/// check_rectified_pair's warnings for the one camera of a mono dataset.
std::vector<std::string> rectified_camera_warnings(const CameraInfo& camera, ImageKind images,
                                                   const std::string& path);

/// For a pair declared rectified: one line per file whose distortion is not
/// zero or whose R is not the identity (the images may be raw). Empty otherwise.
std::vector<std::string> rectified_pair_warnings(const StereoCamera& cameras,
                                                 const std::string& left_path,
                                                 const std::string& right_path);

}  // namespace l2s::io
