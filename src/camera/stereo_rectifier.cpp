// Rectification maps from ROS camera_info (K, D, R, P) with OpenCV:
// initUndistortRectifyMap for plumb_bob (Brown-Conrady), the fisheye variant
// for equidistant; fixed-point maps (1/32 px) and bilinear remap, as ROS's
// image_proc does. Points go through undistortPoints with a tight criterion.
#include <l2s/stereo_rectifier.hpp>

#include <l2s/error.hpp>

#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <cmath>
#include <string>
#include <vector>

namespace l2s {
namespace {

cv::Matx33d to_cv(const Eigen::Matrix3d& m) {
  cv::Matx33d out;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) out(r, c) = m(r, c);
  return out;
}

std::string size_text(int width, int height) {
  return std::to_string(width) + "x" + std::to_string(height);
}

void check_camera(const CameraInfo& camera, const std::string& name) {
  if (camera.width <= 0 || camera.height <= 0)
    throw ParamError(name + ".image_size", size_text(camera.width, camera.height) + " is empty");
  const Eigen::Matrix3d& K = camera.camera_matrix;
  if (!K.allFinite() || !(K(0, 0) > 0.0) || !(K(1, 1) > 0.0))
    throw ParamError(name + ".camera_matrix", "fx and fy must be positive");
  if (!camera.projection_matrix.allFinite() || !(camera.fx() > 0.0) || !(camera.fy() > 0.0))
    throw ParamError(name + ".projection_matrix", "fx and fy must be positive");
  const std::size_t n = camera.distortion_coefficients.size();
  const std::string& model = camera.distortion_model;
  if (model == "plumb_bob") {
    if (n != 4 && n != 5 && n != 8)
      throw ParamError(name + ".distortion_coefficients",
                       std::to_string(n) + " coefficients; plumb_bob takes 4, 5 or 8");
  } else if (model == "equidistant") {
    if (n != 4)
      throw ParamError(name + ".distortion_coefficients",
                       std::to_string(n) + " coefficients; equidistant takes 4");
  } else {
    throw ParamError(name + ".distortion_model",
                     "'" + model + "' is not supported (plumb_bob or equidistant)");
  }
  const Eigen::Matrix3d& R = camera.rectification_matrix;
  if (!((R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() <= 1e-3) ||
      !(R.determinant() > 0.0))
    throw ParamError(name + ".rectification_matrix", "is not a rotation");
}

// A cv::Mat sharing the image's pixels (8-bit, 1 or 3 channels).
cv::Mat view(const Image& image) {
  return cv::Mat(image.height, image.width, image.channels == 1 ? CV_8UC1 : CV_8UC3,
                 const_cast<std::uint8_t*>(image.pixels.data()));
}

}  // namespace

struct CameraRectifier::Maps {
  cv::Mat map1, map2;  // CV_16SC2 + CV_16UC1: fixed-point remap tables
  cv::Matx33d K, R, P;
  std::vector<double> D;
  bool fisheye = false;
};

CameraRectifier::CameraRectifier(const CameraInfo& raw, const std::string& name)
    : maps_(std::make_unique<Maps>()), raw_(raw), name_(name) {
  check_camera(raw, name);
  maps_->K = to_cv(raw.camera_matrix);
  maps_->R = to_cv(raw.rectification_matrix);
  maps_->P = to_cv(raw.projection_matrix.leftCols<3>());
  maps_->D = raw.distortion_coefficients;
  maps_->fisheye = raw.distortion_model == "equidistant";
  const cv::Size size(raw.width, raw.height);
  if (maps_->fisheye)
    cv::fisheye::initUndistortRectifyMap(maps_->K, maps_->D, maps_->R, maps_->P, size, CV_16SC2,
                                         maps_->map1, maps_->map2);
  else
    cv::initUndistortRectifyMap(maps_->K, maps_->D, maps_->R, maps_->P, size, CV_16SC2, maps_->map1,
                                maps_->map2);

  rectified_ = raw;
  rectified_.camera_matrix = raw.projection_matrix.leftCols<3>();
  rectified_.distortion_model = "plumb_bob";
  rectified_.distortion_coefficients.assign(5, 0.0);
  rectified_.rectification_matrix.setIdentity();
  R_rect_camera_ = raw.rectification_matrix;
}

CameraRectifier::~CameraRectifier() = default;
CameraRectifier::CameraRectifier(CameraRectifier&&) noexcept = default;
CameraRectifier& CameraRectifier::operator=(CameraRectifier&&) noexcept = default;

Image CameraRectifier::rectify(const Image& raw) const {
  if (raw.empty() || (raw.channels != 1 && raw.channels != 3) ||
      raw.pixels.size() != static_cast<std::size_t>(raw.width) * raw.height * raw.channels)
    throw ParamError(name_ + " image", "empty, or not an 8-bit image of 1 or 3 channels");
  if (raw.width != raw_.width || raw.height != raw_.height)
    throw ParamError(name_ + " image", size_text(raw.width, raw.height) + ", the camera is " +
                                           size_text(raw_.width, raw_.height));
  Image out(raw.width, raw.height, raw.channels);
  cv::Mat target = view(out);
  cv::remap(view(raw), target, maps_->map1, maps_->map2, cv::INTER_LINEAR, cv::BORDER_CONSTANT);
  return out;
}

Eigen::Vector2d CameraRectifier::rectify_point(const Eigen::Vector2d& raw_px) const {
  const std::vector<cv::Point2d> in{{raw_px.x(), raw_px.y()}};
  std::vector<cv::Point2d> out;
  const cv::TermCriteria converged(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 100, 1e-14);
  if (maps_->fisheye)
    cv::fisheye::undistortPoints(in, out, maps_->K, maps_->D, maps_->R, maps_->P, converged);
  else
    cv::undistortPoints(in, out, maps_->K, maps_->D, maps_->R, maps_->P, converged);
  return {out[0].x, out[0].y};
}

StereoRectifier::StereoRectifier(const StereoCamera& raw)
    : left_(raw.left, "left"), right_(raw.right, "right") {
  if (raw.left.width != raw.right.width || raw.left.height != raw.right.height)
    throw ParamError("cameras", "left " + size_text(raw.left.width, raw.left.height) +
                                    " and right " + size_text(raw.right.width, raw.right.height) +
                                    " images differ in size");
  rectified_.left = left_.rectified();
  rectified_.right = right_.rectified();
  rectified_.images = ImageKind::Rectified;
}

RectifiedPair StereoRectifier::rectify(const Image& left, const Image& right) const {
  return {left_.rectify(left), right_.rectify(right)};
}

Eigen::Isometry3d StereoRectifier::T_rect_camera() const {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = R_rect_camera();
  return T;
}

}  // namespace l2s
