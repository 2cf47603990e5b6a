// Stereo pair checks. A rectified pair needs only P to be consistent; a raw
// pair also needs K, D and R good enough to build rectification maps from, and
// the errors say which file and key to fix.
#include "io/stereo_check.hpp"

#include <l2s/error.hpp>

#include <Eigen/LU>

#include <cmath>
#include <sstream>

namespace l2s::io {
namespace {

constexpr double kPixelTolerance = 1e-3;     // [px] files round P to a few decimals
constexpr double kRotationTolerance = 1e-3;  // max |R^T R - I|: R printed with few decimals
constexpr double kIdentityTolerance = 1e-6;  // below this R counts as the identity

std::string size_of(const CameraInfo& c) {
  return std::to_string(c.width) + "x" + std::to_string(c.height);
}

std::string number(double value) {
  std::ostringstream text;
  text.precision(10);
  text << value;
  return text.str();
}

void check_camera_matrix(const CameraInfo& camera, const std::string& path) {
  const Eigen::Matrix3d& K = camera.camera_matrix;
  if (!K.allFinite() || !(K(0, 0) > 0.0) || !(K(1, 1) > 0.0))
    throw FileError(path, "camera_matrix: fx and fy must be positive");
  if (K(1, 0) != 0.0 || K(2, 0) != 0.0 || K(2, 1) != 0.0 || K(2, 2) != 1.0)
    throw FileError(path, "camera_matrix: expected [fx s cx; 0 fy cy; 0 0 1]");
  if (!(K(0, 2) > 0.0 && K(0, 2) < camera.width && K(1, 2) > 0.0 && K(1, 2) < camera.height))
    throw FileError(path, "camera_matrix: principal point (" + number(K(0, 2)) + ", " +
                              number(K(1, 2)) + ") lies outside the " + size_of(camera) + " image");
}

void check_distortion(const CameraInfo& camera, const std::string& path) {
  const std::size_t n = camera.distortion_coefficients.size();
  const std::string count = std::to_string(n) + " distortion_coefficients";
  if (camera.distortion_model == "plumb_bob") {
    if (n != 4 && n != 5 && n != 8)
      throw FileError(path, count + " do not fit distortion_model plumb_bob (4, 5 or 8)");
  } else if (camera.distortion_model == "equidistant") {
    if (n != 4) throw FileError(path, count + " do not fit distortion_model equidistant (4)");
  } else {
    throw FileError(path, "distortion_model '" + camera.distortion_model +
                              "' is not supported for raw images (plumb_bob or equidistant)");
  }
  for (double d : camera.distortion_coefficients)
    if (!std::isfinite(d)) throw FileError(path, "distortion_coefficients must be finite");
}

void check_rotation(const Eigen::Matrix3d& R, const std::string& path) {
  const double error = (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  if (!(error <= kRotationTolerance) || !(R.determinant() > 0.0))
    throw FileError(path, "rectification_matrix is not a rotation (max |R^T R - I| = " +
                              number(error) + ", det " + number(R.determinant()) + ")");
}

bool has_distortion(const CameraInfo& camera) {
  for (double d : camera.distortion_coefficients)
    if (d != 0.0) return true;
  return false;
}

}  // namespace

void check_rectified_pair(const StereoCamera& cameras, const std::string& left_path,
                          const std::string& right_path) {
  const CameraInfo& l = cameras.left;
  const CameraInfo& r = cameras.right;
  if (l.width != r.width || l.height != r.height)
    throw FileError(right_path, "image size " + size_of(r) + " differs from " + left_path + " (" +
                                    size_of(l) + "); a rectified pair shares its size");
  const auto require_same = [&](double left_value, double right_value, const char* name) {
    if (std::abs(left_value - right_value) > kPixelTolerance)
      throw FileError(right_path, std::string("projection_matrix ") + name + " = " +
                                      number(right_value) + " differs from " + left_path + " (" +
                                      number(left_value) + "); the pair is not rectified");
  };
  require_same(l.fx(), r.fx(), "fx");
  require_same(l.fy(), r.fy(), "fy");
  require_same(l.cy(), r.cy(), "cy");
  // The left camera is the reference: its P has no baseline term (|Tx| < 1 mm).
  if (std::abs(l.projection_matrix(0, 3)) > 1e-3 * l.fx())
    throw FileError(left_path, "projection_matrix P[0][3] must be 0 for the left camera");
  if (!(cameras.baseline() > 0.0))
    throw FileError(right_path, "baseline -P[0][3]/fx = " + number(cameras.baseline()) +
                                    " m must be positive (is this the left camera?)");
}

void check_raw_pair(const StereoCamera& cameras, const std::string& left_path,
                    const std::string& right_path) {
  const CameraInfo& l = cameras.left;
  const CameraInfo& r = cameras.right;
  if (l.width != r.width || l.height != r.height)
    throw FileError(right_path, "image size " + size_of(r) + " differs from " + left_path + " (" +
                                    size_of(l) + "); both cameras must deliver one size");
  for (const auto& [camera, path] : {std::pair{&l, &left_path}, std::pair{&r, &right_path}}) {
    check_camera_matrix(*camera, *path);
    check_distortion(*camera, *path);
    check_rotation(camera->rectification_matrix, *path);
  }
  check_rectified_pair(cameras, left_path, right_path);  // P: the rectified pair to produce
}

void check_pair(const StereoCamera& cameras, const std::string& left_path,
                const std::string& right_path) {
  if (cameras.images == ImageKind::Raw)
    check_raw_pair(cameras, left_path, right_path);
  else
    check_rectified_pair(cameras, left_path, right_path);
}

void check_single_camera(const CameraInfo& camera, ImageKind images, const std::string& path) {
  if (images == ImageKind::Raw) {
    check_camera_matrix(camera, path);
    check_distortion(camera, path);
    check_rotation(camera.rectification_matrix, path);
  }
  if (std::abs(camera.projection_matrix(0, 3)) > 1e-3 * camera.fx())
    throw FileError(path, "projection_matrix P[0][3] must be 0 for the left camera");
}

std::vector<std::string> rectified_camera_warnings(const CameraInfo& camera, ImageKind images,
                                                   const std::string& path) {
  StereoCamera pair{camera, camera, images};
  std::vector<std::string> warnings = rectified_pair_warnings(pair, path, path);
  warnings.resize(warnings.size() / 2);  // the second camera's lines repeat the first's
  return warnings;
}

std::vector<std::string> rectified_pair_warnings(const StereoCamera& cameras,
                                                 const std::string& left_path,
                                                 const std::string& right_path) {
  std::vector<std::string> warnings;
  if (cameras.images != ImageKind::Rectified) return warnings;
  const std::string hint =
      " but the images are declared rectified (dataset.yaml images: rectified, the default), "
      "so only P is used; if the images are raw, write `images: raw` in dataset.yaml";
  for (const auto& [camera, path] :
       {std::pair{&cameras.left, &left_path}, std::pair{&cameras.right, &right_path}}) {
    if (has_distortion(*camera))
      warnings.push_back(*path + ": distortion_coefficients are not zero" + hint);
    const Eigen::Matrix3d& R = camera->rectification_matrix;
    if ((R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() > kIdentityTolerance)
      warnings.push_back(*path + ": rectification_matrix is not the identity" + hint);
  }
  return warnings;
}

}  // namespace l2s::io
