// The camera messages of a ROS 1 recording: images in each encoding drivers
// publish (padded rows, 16 bits either byte order, RGB order, alpha, Bayer
// mosaics), compressed images, and camera_info, decoded into the library's
// images and camera models.

#include <l2s/error.hpp>
#include <l2s/recording/point_cloud2.hpp>
#include <l2s/recording/ros_messages.hpp>

#include "support/ros1_bag_writer.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>

namespace {

using l2s::test::image_message;

constexpr std::int64_t kStamp = 1700000001LL * 1000000000LL + 5000;
constexpr int kWidth = 40, kHeight = 30;

/// A BGR test picture whose channels differ everywhere.
std::uint8_t bgr(int x, int y, int c) { return static_cast<std::uint8_t>((x * 5 + y * 3 + c * 70) % 256); }

TEST(RecordedImage, Mono8WithPaddedRowsKeepsItsPixels) {
  const std::uint32_t step = kWidth + 8;
  std::vector<std::uint8_t> pixels(step * kHeight, 0xAB);
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) pixels[y * step + x] = bgr(x, y, 0);
  const auto decoded = l2s::decode_image(image_message(kStamp, "left_optical", kWidth, kHeight, "mono8", step, pixels));
  EXPECT_EQ(decoded.stamp_ns, kStamp);
  EXPECT_EQ(decoded.frame_id, "left_optical");
  ASSERT_EQ(decoded.image.channels, 1);
  ASSERT_EQ(decoded.image.width, kWidth);
  ASSERT_EQ(decoded.image.height, kHeight);
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) ASSERT_EQ(decoded.image.at(x, y), bgr(x, y, 0)) << x << "," << y;
}

TEST(RecordedImage, Mono16IsScaledToEightBitsInEitherByteOrder) {
  for (const bool big_endian : {false, true}) {
    std::vector<std::uint8_t> pixels(kWidth * kHeight * 2);
    for (int i = 0; i < kWidth * kHeight; ++i) {
      const auto value = static_cast<std::uint16_t>(i * 50);
      pixels[2 * i + (big_endian ? 0 : 1)] = static_cast<std::uint8_t>(value >> 8);
      pixels[2 * i + (big_endian ? 1 : 0)] = static_cast<std::uint8_t>(value & 0xFF);
    }
    const auto decoded = l2s::decode_image(
        image_message(kStamp, "cam", kWidth, kHeight, "mono16", kWidth * 2, pixels, big_endian));
    ASSERT_EQ(decoded.image.channels, 1);
    for (int i = 0; i < kWidth * kHeight; i += 97)
      EXPECT_NEAR(decoded.image.pixels[i], (i * 50) / 256.0, 0.51) << "pixel " << i << (big_endian ? " big" : " little");
  }
}

TEST(RecordedImage, ColourEncodingsComeBackAsBgr) {
  struct Case {
    const char* encoding;
    int channels;
    int order[4];  ///< which BGR channel each stored channel holds (-1: alpha)
  };
  for (const Case& c : {Case{"bgr8", 3, {0, 1, 2}}, Case{"rgb8", 3, {2, 1, 0}}, Case{"bgra8", 4, {0, 1, 2, -1}},
                        Case{"rgba8", 4, {2, 1, 0, -1}}}) {
    std::vector<std::uint8_t> pixels;
    for (int y = 0; y < kHeight; ++y)
      for (int x = 0; x < kWidth; ++x)
        for (int k = 0; k < c.channels; ++k) pixels.push_back(c.order[k] < 0 ? 255 : bgr(x, y, c.order[k]));
    const auto decoded = l2s::decode_image(
        image_message(kStamp, "cam", kWidth, kHeight, c.encoding, kWidth * c.channels, pixels));
    ASSERT_EQ(decoded.image.channels, 3) << c.encoding;
    for (int y = 0; y < kHeight; ++y)
      for (int x = 0; x < kWidth; ++x)
        for (int k = 0; k < 3; ++k) ASSERT_EQ(decoded.image.at(x, y, k), bgr(x, y, k)) << c.encoding;
  }
}

// A flat colour through each mosaic: demosaicing gives it back inside the
// image, and a pattern mapped to the wrong OpenCV code swaps red and blue.
TEST(RecordedImage, BayerMosaicsDemosaicToTheirColours) {
  const std::uint8_t colour[3] = {40, 120, 200};  // B, G, R
  // Which colour (0 B, 1 G, 2 R) each pattern puts at (x % 2, y % 2), row-major from the top left.
  const std::pair<const char*, std::array<int, 4>> patterns[] = {
      {"bayer_rggb8", {2, 1, 1, 0}}, {"bayer_bggr8", {0, 1, 1, 2}},
      {"bayer_gbrg8", {1, 0, 2, 1}}, {"bayer_grbg8", {1, 2, 0, 1}}};
  for (const auto& [encoding, layout] : patterns) {
    std::vector<std::uint8_t> mosaic(kWidth * kHeight);
    for (int y = 0; y < kHeight; ++y)
      for (int x = 0; x < kWidth; ++x) mosaic[y * kWidth + x] = colour[layout[(y % 2) * 2 + x % 2]];
    const auto decoded = l2s::decode_image(image_message(kStamp, "cam", kWidth, kHeight, encoding, kWidth, mosaic));
    ASSERT_EQ(decoded.image.channels, 3) << encoding;
    for (int k = 0; k < 3; ++k) EXPECT_EQ(decoded.image.at(kWidth / 2, kHeight / 2, k), colour[k]) << encoding << " channel " << k;
  }
}

TEST(RecordedImage, CompressedPngIsLosslessAndJpegClose) {
  cv::Mat picture(kHeight, kWidth, CV_8UC3);
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x)
      for (int k = 0; k < 3; ++k) picture.at<cv::Vec3b>(y, x)[k] = bgr(x, y, k) / 2 + 60;  // smooth enough for jpeg
  for (const char* format : {"png", "jpeg"}) {
    std::vector<std::uint8_t> bytes;
    ASSERT_TRUE(cv::imencode(std::string(".") + (format[0] == 'p' ? "png" : "jpg"), picture, bytes));
    const auto decoded = l2s::decode_compressed_image(l2s::test::compressed_image_message(kStamp, "cam", format, bytes));
    ASSERT_EQ(decoded.image.channels, 3);
    ASSERT_EQ(decoded.image.width, kWidth);
    double worst = 0.0, sum = 0.0;
    for (int y = 0; y < kHeight; ++y)
      for (int x = 0; x < kWidth; ++x)
        for (int k = 0; k < 3; ++k) {
          const double error = std::abs(double(decoded.image.at(x, y, k)) - picture.at<cv::Vec3b>(y, x)[k]);
          worst = std::max(worst, error);
          sum += error;
        }
    if (format[0] == 'p')
      EXPECT_EQ(worst, 0.0) << format;
    else
      EXPECT_LE(sum / (kWidth * kHeight * 3), 5.0) << format;  // jpeg's blocks blur the picture's edges
  }
  EXPECT_THROW(l2s::decode_compressed_image(
                   l2s::test::compressed_image_message(kStamp, "cam", "png", std::vector<std::uint8_t>(100, 7))),
               l2s::InputError);
}

TEST(RecordedImage, AnUnknownEncodingOrShortRowsAreNamed) {
  const std::vector<std::uint8_t> pixels(kWidth * kHeight * 3, 1);
  try {
    l2s::decode_image(image_message(kStamp, "cam", kWidth, kHeight, "yuv422", kWidth * 2, pixels));
    FAIL() << "yuv422 was decoded";
  } catch (const l2s::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("Image message: encoding 'yuv422'"), std::string::npos) << e.what();
  }
  EXPECT_THROW(l2s::decode_image(image_message(kStamp, "cam", kWidth, kHeight, "bgr8", kWidth, pixels)),
               l2s::InputError);
  auto cut = image_message(kStamp, "cam", kWidth, kHeight, "bgr8", kWidth * 3, pixels);
  cut.resize(cut.size() - 10);
  EXPECT_THROW(l2s::decode_image(cut), l2s::InputError);
}

// Found by fuzzing (fuzz/ros1_bag_fuzzer.cpp): a header may state anything.
TEST(RecordedImage, AHeaderStatingGigapixelsIsRefusedBeforeDecoding) {
  std::vector<std::uint8_t> png;
  ASSERT_TRUE(cv::imencode(".png", cv::Mat(6, 8, CV_8UC1, cv::Scalar(9)), png));
  const std::uint8_t huge[8] = {0, 1, 0x86, 0xA0, 0, 1, 0x86, 0xA0};  // IHDR: 100000 x 100000 px
  std::copy(huge, huge + 8, png.begin() + 16);
  try {
    l2s::decode_compressed_image(l2s::test::compressed_image_message(kStamp, "cam", "png", png));
    FAIL() << "a 10-gigapixel png was decoded";
  } catch (const l2s::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("100000x100000 px, more than 64 megapixels"), std::string::npos) << e.what();
  }
}

TEST(PointCloud2Empty, BillionsOfEmptyRowsDecodeAtOnce) {
  const auto message = l2s::test::point_cloud2_message(l2s::LidarCloud{}, {{"x", 7}, {"y", 7}, {"z", 7}}, kStamp,
                                                       "velodyne", 4000000000u);
  const auto sweep = l2s::decode_point_cloud2(message);  // 4e9 rows of nothing: no loop over them
  EXPECT_EQ(sweep.height, 4000000000u);
  EXPECT_TRUE(sweep.cloud.empty());
}

TEST(RecordedCameraInfo, KeepsTheWholeModel) {
  l2s::CameraInfo camera = l2s::CameraInfo::ideal("right", 1280, 960, 1000.5, 640.25, 479.75, 0.12);
  camera.camera_matrix << 998.0, 0.0, 641.0, 0.0, 997.0, 478.0, 0.0, 0.0, 1.0;
  camera.distortion_coefficients = {-0.21, 0.05, 0.001, -0.0005, 0.0};
  camera.rectification_matrix = Eigen::AngleAxisd(0.01, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const auto decoded = l2s::decode_camera_info(l2s::test::camera_info_message(kStamp, "right_optical", camera));
  EXPECT_EQ(decoded.stamp_ns, kStamp);
  EXPECT_EQ(decoded.camera.camera_name, "right_optical");
  EXPECT_EQ(decoded.camera.width, 1280);
  EXPECT_EQ(decoded.camera.height, 960);
  EXPECT_EQ(decoded.camera.distortion_model, "plumb_bob");
  EXPECT_EQ(decoded.camera.distortion_coefficients, camera.distortion_coefficients);
  EXPECT_EQ(decoded.camera.camera_matrix, camera.camera_matrix);
  EXPECT_EQ(decoded.camera.rectification_matrix, camera.rectification_matrix);
  EXPECT_EQ(decoded.camera.projection_matrix, camera.projection_matrix);

  l2s::CameraInfo uncalibrated = camera;
  uncalibrated.projection_matrix.setZero();
  EXPECT_THROW(l2s::decode_camera_info(l2s::test::camera_info_message(kStamp, "cam", uncalibrated)), l2s::InputError);
  auto cut = l2s::test::camera_info_message(kStamp, "cam", camera);
  cut.resize(60);
  EXPECT_THROW(l2s::decode_camera_info(cut), l2s::InputError);
}

}  // namespace
