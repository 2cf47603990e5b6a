// Rectification of raw images against OpenCV's own forward models: a pattern
// of dots placed in the rectified image is drawn into a raw image where
// cv::projectPoints (plumb_bob) or cv::fisheye::distortPoints (equidistant)
// put it; rectifying that image must bring every dot back. And 3D points seen
// by a raw stereo pair, rectified and triangulated in the rectified frame,
// must come back to the camera's own frame through T_rect_camera.
#include <l2s/error.hpp>
#include <l2s/stereo_rectifier.hpp>

#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>

#include <Eigen/Geometry>
#include <cmath>
#include <vector>

namespace l2s {
namespace {

constexpr int kWidth = 800, kHeight = 600;
constexpr double kDeg = M_PI / 180.0;

Eigen::Matrix3d rotation(double x_deg, double y_deg, double z_deg) {
  return (Eigen::AngleAxisd(z_deg * kDeg, Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(y_deg * kDeg, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(x_deg * kDeg, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

// A raw camera: K with a distorted lens, R, and P of the rectified image
// (focal length 560 px, baseline `baseline` for the right camera).
CameraInfo raw_camera(const std::string& model, const Eigen::Matrix3d& R, double baseline = 0.0) {
  CameraInfo camera = CameraInfo::ideal("raw", kWidth, kHeight, 560.0, 399.5, 299.5, baseline);
  camera.camera_matrix << 600.0, 0.0, 402.3, 0.0, 601.5, 297.1, 0.0, 0.0, 1.0;
  camera.distortion_model = model;
  camera.distortion_coefficients = model == "equidistant"
                                       ? std::vector<double>{0.08, -0.02, 0.004, -0.0005}
                                       : std::vector<double>{-0.28, 0.09, 0.0008, -0.0006, -0.012};
  camera.rectification_matrix = R;
  return camera;
}

// Raw pixels of points given in the raw camera's frame, by OpenCV's models.
std::vector<Eigen::Vector2d> project_raw(const CameraInfo& camera,
                                         const std::vector<Eigen::Vector3d>& points) {
  cv::Matx33d K;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) K(r, c) = camera.camera_matrix(r, c);
  std::vector<cv::Point2d> pixels;
  if (camera.distortion_model == "equidistant") {
    std::vector<cv::Point2d> normalized;
    for (const Eigen::Vector3d& p : points) normalized.emplace_back(p.x() / p.z(), p.y() / p.z());
    cv::fisheye::distortPoints(normalized, pixels, K, camera.distortion_coefficients);
  } else {
    std::vector<cv::Point3d> objects;
    for (const Eigen::Vector3d& p : points) objects.emplace_back(p.x(), p.y(), p.z());
    cv::projectPoints(objects, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), K,
                      camera.distortion_coefficients, pixels);
  }
  std::vector<Eigen::Vector2d> out;
  for (const cv::Point2d& p : pixels) out.emplace_back(p.x, p.y);
  return out;
}

// The ray of a rectified pixel, in the raw camera's frame.
Eigen::Vector3d ray_of_rectified_pixel(const CameraInfo& camera, const Eigen::Vector2d& px) {
  const Eigen::Vector3d in_rect((px.x() - camera.cx()) / camera.fx(),
                                (px.y() - camera.cy()) / camera.fy(), 1.0);
  return camera.rectification_matrix.transpose() * in_rect;
}

// Gaussian dots (sigma 1.3 px) on a dark background.
Image draw_dots(const std::vector<Eigen::Vector2d>& centres) {
  Image image(kWidth, kHeight, 1, 20);
  for (const Eigen::Vector2d& c : centres)
    for (int y = static_cast<int>(c.y()) - 5; y <= static_cast<int>(c.y()) + 6; ++y)
      for (int x = static_cast<int>(c.x()) - 5; x <= static_cast<int>(c.x()) + 6; ++x) {
        if (x < 0 || y < 0 || x >= kWidth || y >= kHeight) continue;
        const double r2 = (x - c.x()) * (x - c.x()) + (y - c.y()) * (y - c.y());
        image.at(x, y) = static_cast<std::uint8_t>(
            std::min(255.0, image.at(x, y) + 220.0 * std::exp(-r2 / (2.0 * 1.3 * 1.3))));
      }
  return image;
}

// Background-subtracted centroid in a window around `guess`.
Eigen::Vector2d centroid(const Image& image, const Eigen::Vector2d& guess) {
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  double weight = 0.0;
  for (int y = static_cast<int>(std::lround(guess.y())) - 5; y <= std::lround(guess.y()) + 5; ++y)
    for (int x = static_cast<int>(std::lround(guess.x())) - 5; x <= std::lround(guess.x()) + 5;
         ++x) {
      const double w = std::max(0.0, image.at(x, y) - 20.0);
      sum += w * Eigen::Vector2d(x, y);
      weight += w;
    }
  return sum / weight;
}

// Dots on a grid over the rectified image, drawn into the raw image where the
// lens puts them; rectified, they are back within `tolerance` px (mean) of
// where they were placed. Returns the largest error.
double round_trip_error(const CameraRectifier& rectifier, const CameraInfo& raw, double* mean) {
  std::vector<Eigen::Vector2d> placed;
  std::vector<Eigen::Vector3d> rays;
  for (double y = 40.0; y < kHeight - 40; y += 48.7)
    for (double x = 40.0; x < kWidth - 40; x += 51.3) {
      placed.emplace_back(x, y);
      rays.push_back(ray_of_rectified_pixel(raw, placed.back()));
    }
  const Image rectified = rectifier.rectify(draw_dots(project_raw(raw, rays)));
  double largest = 0.0, total = 0.0;
  for (const Eigen::Vector2d& p : placed) {
    const double error = (centroid(rectified, p) - p).norm();
    largest = std::max(largest, error);
    total += error;
  }
  *mean = total / placed.size();
  return largest;
}

TEST(CameraRectifier, BringsDistortedDotsBackToTheirRectifiedPlace) {
  for (const char* model : {"plumb_bob", "equidistant"}) {
    const CameraInfo raw = raw_camera(model, rotation(0.7, -1.2, 0.3));
    const CameraRectifier rectifier(raw, "left");
    double mean = 0.0;
    const double largest = round_trip_error(rectifier, raw, &mean);
    EXPECT_LT(mean, 0.05) << model;
    EXPECT_LT(largest, 0.15) << model;
    RecordProperty(std::string(model) + "_mean_px", std::to_string(mean));
    RecordProperty(std::string(model) + "_max_px", std::to_string(largest));
  }
}

// Mono: R the identity and P the camera's new matrix is undistortion.
TEST(CameraRectifier, UndistortsAMonoCamera) {
  const CameraInfo raw = raw_camera("plumb_bob", Eigen::Matrix3d::Identity());
  const CameraRectifier undistorter(raw);
  double mean = 0.0;
  EXPECT_LT(round_trip_error(undistorter, raw, &mean), 0.15);
  EXPECT_LT(mean, 0.05);
  const std::vector<Eigen::Vector2d> raw_px = project_raw(raw, {Eigen::Vector3d(0.3, -0.2, 1.0)});
  const Eigen::Vector2d ideal(raw.fx() * 0.3 + raw.cx(), raw.fy() * -0.2 + raw.cy());
  EXPECT_LT((undistorter.rectify_point(raw_px[0]) - ideal).norm(), 1e-6);
}

TEST(CameraRectifier, KeepsChannelsAndDescribesTheRectifiedCamera) {
  const CameraInfo raw = raw_camera("plumb_bob", rotation(1.0, 0.0, 0.0));
  const CameraRectifier rectifier(raw);
  const Image colour(kWidth, kHeight, 3, 90);
  const Image out = rectifier.rectify(colour);
  EXPECT_EQ(out.channels, 3);
  EXPECT_EQ(out.at(kWidth / 2, kHeight / 2, 2), 90);
  EXPECT_EQ(rectifier.rectified().camera_matrix, raw.projection_matrix.leftCols<3>());
  EXPECT_EQ(rectifier.rectified().distortion_coefficients, std::vector<double>(5, 0.0));
  EXPECT_TRUE(rectifier.rectified().rectification_matrix.isIdentity());
  EXPECT_EQ(rectifier.rectified().projection_matrix, raw.projection_matrix);
  EXPECT_EQ(rectifier.R_rect_camera(), raw.rectification_matrix);
}

TEST(CameraRectifier, RejectsWhatItCannotRectify) {
  CameraInfo raw = raw_camera("plumb_bob", Eigen::Matrix3d::Identity());
  raw.distortion_model = "rational_polynomial";
  try {
    CameraRectifier rectifier(raw, "left");
    ADD_FAILURE() << "no error";
  } catch (const ParamError& e) {
    EXPECT_EQ(e.field(), "left.distortion_model");
    EXPECT_NE(std::string(e.what()).find("'rational_polynomial'"), std::string::npos) << e.what();
  }
  raw = raw_camera("equidistant", Eigen::Matrix3d::Identity());
  raw.distortion_coefficients.push_back(0.0);
  EXPECT_THROW(CameraRectifier{raw}, ParamError);
  raw = raw_camera("plumb_bob", Eigen::Matrix3d::Identity());
  raw.rectification_matrix(2, 2) = -1.0;
  EXPECT_THROW(CameraRectifier{raw}, ParamError);

  const CameraRectifier rectifier(raw_camera("plumb_bob", Eigen::Matrix3d::Identity()), "left");
  try {
    rectifier.rectify(Image(kWidth + 1, kHeight));
    ADD_FAILURE() << "no error";
  } catch (const ParamError& e) {
    EXPECT_EQ(e.field(), "left image");
    EXPECT_NE(std::string(e.what()).find("801x600, the camera is 800x600"), std::string::npos);
  }
  EXPECT_THROW(rectifier.rectify(Image()), ParamError);
}

// A raw pair: the physical right camera sits at the baseline along the
// rectified x axis; each camera has its own K, D and R.
StereoCamera raw_pair(const std::string& model) {
  StereoCamera pair;
  pair.images = ImageKind::Raw;
  pair.left = raw_camera(model, rotation(0.7, -1.2, 0.3));
  pair.right = raw_camera(model, rotation(0.4, 0.9, -0.2), 0.2);
  pair.right.camera_matrix << 598.0, 0.0, 396.8, 0.0, 598.9, 303.0, 0.0, 0.0, 1.0;
  return pair;
}

// Points in the physical left camera's frame, seen by both raw cameras,
// rectified, triangulated in the rectified frame and brought back with
// T_rect_camera, are where they were.
TEST(StereoRectifier, TriangulatedPointsReturnToTheCameraFrame) {
  for (const char* model : {"plumb_bob", "equidistant"}) {
    const StereoCamera raw = raw_pair(model);
    const StereoRectifier rectifier(raw);
    const double B = rectifier.rectified().baseline(), f = raw.left.fx();
    std::vector<Eigen::Vector3d> points_camera, points_right;
    for (double z : {2.0, 4.5, 8.0})
      for (double x : {-0.8, 0.0, 0.9})
        for (double y : {-0.5, 0.1, 0.6}) {
          const Eigen::Vector3d p(x * z / 2.0, y * z / 2.0, z);
          points_camera.push_back(p);
          // p_rect_right = p_rect - (B, 0, 0) = R_right * p_right_camera.
          points_right.push_back(raw.right.rectification_matrix.transpose() *
                                 (raw.left.rectification_matrix * p - Eigen::Vector3d(B, 0, 0)));
        }
    const auto left_px = project_raw(raw.left, points_camera);
    const auto right_px = project_raw(raw.right, points_right);
    for (std::size_t i = 0; i < points_camera.size(); ++i) {
      const Eigen::Vector2d l = rectifier.left().rectify_point(left_px[i]);
      const Eigen::Vector2d r = rectifier.right().rectify_point(right_px[i]);
      EXPECT_NEAR(l.y(), r.y(), 1e-6) << model << " " << i;  // rows line up
      const double z = f * B / (l.x() - r.x());
      const Eigen::Vector3d p_rect((l.x() - raw.left.cx()) * z / f, (l.y() - raw.left.cy()) * z / f,
                                   z);
      const Eigen::Vector3d back = rectifier.T_rect_camera().inverse() * p_rect;
      EXPECT_LT((back - points_camera[i]).norm(), 1e-6 * z) << model << " " << i;
    }
  }
}

// A pose found in the rectified frame converts to the camera frame by
// T_lidar_camera = T_lidar_rect * T_rect_camera.
TEST(StereoRectifier, ConvertsAPoseFoundInTheRectifiedFrame) {
  const StereoRectifier rectifier(raw_pair("plumb_bob"));
  Eigen::Isometry3d T_lidar_rect = Eigen::Isometry3d::Identity();
  T_lidar_rect.linear() = rotation(-90.0, 0.0, -90.0);
  T_lidar_rect.translation() << 0.3, -0.1, 0.2;
  const Eigen::Isometry3d T_lidar_camera = T_lidar_rect * rectifier.T_rect_camera();
  const Eigen::Vector3d p_camera(0.4, -0.3, 5.0);
  const Eigen::Vector3d p_rect = rectifier.R_rect_camera() * p_camera;
  EXPECT_LT((T_lidar_camera * p_camera - T_lidar_rect * p_rect).norm(), 1e-12);
  EXPECT_LT((rectifier.T_rect_camera().translation()).norm(), 1e-15);
}

// The same through images: dots drawn where both raw cameras see 3D points,
// both images rectified, the dots found and triangulated.
TEST(StereoRectifier, RectifiedImagesTriangulateToTheCameraFrame) {
  const StereoCamera raw = raw_pair("plumb_bob");
  const StereoRectifier rectifier(raw);
  const double B = rectifier.rectified().baseline(), f = raw.left.fx();
  std::vector<Eigen::Vector3d> points_camera, points_right;
  for (double x : {-1.0, -0.2, 0.7})
    for (double y : {-0.5, 0.4}) {
      points_camera.emplace_back(x, y, 3.0);
      points_right.push_back(
          raw.right.rectification_matrix.transpose() *
          (raw.left.rectification_matrix * points_camera.back() - Eigen::Vector3d(B, 0, 0)));
    }
  const auto left_px = project_raw(raw.left, points_camera);
  const auto right_px = project_raw(raw.right, points_right);
  const RectifiedPair images = rectifier.rectify(draw_dots(left_px), draw_dots(right_px));
  for (std::size_t i = 0; i < points_camera.size(); ++i) {
    const Eigen::Vector2d l = centroid(images.left, rectifier.left().rectify_point(left_px[i]));
    const Eigen::Vector2d r = centroid(images.right, rectifier.right().rectify_point(right_px[i]));
    EXPECT_NEAR(l.y(), r.y(), 0.1) << i;
    const double z = f * B / (l.x() - r.x());
    const Eigen::Vector3d p_rect((l.x() - raw.left.cx()) * z / f, (l.y() - raw.left.cy()) * z / f,
                                 z);
    const Eigen::Vector3d back = rectifier.T_rect_camera().inverse() * p_rect;
    EXPECT_LT((back - points_camera[i]).norm(), 0.01) << i;  // 0.1 px of 37 px disparity
  }
}

TEST(StereoRectifier, DescribesTheRectifiedPair) {
  const StereoCamera raw = raw_pair("plumb_bob");
  const StereoRectifier rectifier(raw);
  EXPECT_EQ(rectifier.rectified().images, ImageKind::Rectified);
  EXPECT_DOUBLE_EQ(rectifier.rectified().baseline(), raw.baseline());
  EXPECT_EQ(rectifier.R_rect_camera(), raw.left.rectification_matrix);
  EXPECT_TRUE(rectifier.rectified().right.rectification_matrix.isIdentity());
}

TEST(StereoRectifier, RejectsPairsOfDifferentSizesAndImagesOfTheWrongSize) {
  StereoCamera raw = raw_pair("plumb_bob");
  raw.right.width = kWidth + 2;
  EXPECT_THROW(StereoRectifier{raw}, ParamError);
  raw = raw_pair("plumb_bob");
  raw.right.distortion_model = "fisheye";
  try {
    StereoRectifier rectifier(raw);
    ADD_FAILURE() << "no error";
  } catch (const ParamError& e) {
    EXPECT_EQ(e.field(), "right.distortion_model");
  }
  const StereoRectifier rectifier(raw_pair("plumb_bob"));
  try {
    rectifier.rectify(Image(kWidth, kHeight), Image(kWidth, kHeight - 1));
    ADD_FAILURE() << "no error";
  } catch (const ParamError& e) {
    EXPECT_EQ(e.field(), "right image");
  }
}

}  // namespace
}  // namespace l2s
