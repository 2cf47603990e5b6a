// Camera YAML (ROS camera_info): round trips, real-file variations, bad input.
#include <l2s/error.hpp>
#include <l2s/io/camera_yaml.hpp>

#include "io_test_helpers.hpp"
#include "support/test_data.hpp"

#include <gtest/gtest.h>

namespace l2s::io {
namespace {

// As written by ROS camera_calibration for a rectified stereo pair.
const char* kRosLeft = R"(image_width: 1024
image_height: 768
camera_name: narrow_stereo/left
camera_matrix:
  rows: 3
  cols: 3
  data: [ 704.5, 0, 512.25, 0, 704.5, 384.75, 0, 0, 1]
distortion_model: plumb_bob
distortion_coefficients:
  rows: 1
  cols: 5
  data: [-0.1, 0.01, 0.0001, -0.0002, 0]
rectification_matrix:
  rows: 3
  cols: 3
  data: [ 1, 0, 0, 0, 1, 0, 0, 0, 1]
projection_matrix:
  rows: 3
  cols: 4
  data: [ 650.0, 0, 500.0, 0, 0, 650.0, 380.0, 0, 0, 0, 1, 0]
)";

std::string right_of(const std::string& left_text, const std::string& tx) {
  std::string text = left_text;
  const std::string from = "[ 650.0, 0, 500.0, 0,";
  text.replace(text.find(from), from.size(), "[ 650.0, 0, 500.0, " + tx + ",");
  return text;
}

TEST(CameraYaml, ReadsRosCalibrationFile) {
  test::TempDir dir;
  test::write_text(dir.file("left.yaml"), kRosLeft);
  const CameraInfo camera = read_camera_info(dir.file("left.yaml"));
  EXPECT_EQ(camera.camera_name, "narrow_stereo/left");
  EXPECT_EQ(camera.width, 1024);
  EXPECT_EQ(camera.height, 768);
  EXPECT_EQ(camera.camera_matrix(0, 2), 512.25);
  EXPECT_EQ(camera.distortion_model, "plumb_bob");
  EXPECT_EQ(camera.distortion_coefficients, (std::vector<double>{-0.1, 0.01, 0.0001, -0.0002, 0}));
  EXPECT_EQ(camera.fx(), 650.0);
  EXPECT_EQ(camera.fy(), 650.0);
  EXPECT_EQ(camera.cx(), 500.0);
  EXPECT_EQ(camera.cy(), 380.0);
}

TEST(CameraYaml, RoundTripsEveryFieldExactly) {
  test::TempDir dir;
  CameraInfo camera = CameraInfo::ideal("right cam", 1280, 720, 1000.0 / 3.0, 640.1, 360.7, 0.12);
  camera.camera_matrix(0, 1) = 1e-7;
  camera.rectification_matrix << 0.9999, 0.01, -1e-5, -0.01, 0.9999, 2e-20, 1e-5, 0, 1;
  for (const std::vector<double>& d : {std::vector<double>{},
                                       {0.1, -0.2, 0.003, 1e-9},
                                       {1, 2, 3, 4, 5},
                                       {1, 2, 3, 4, 5, 6, 7, 8}}) {
    camera.distortion_coefficients = d;
    write_camera_info(dir.file("cam.yaml"), camera);
    const CameraInfo back = read_camera_info(dir.file("cam.yaml"));
    EXPECT_EQ(back.camera_name, camera.camera_name);
    EXPECT_EQ(back.width, camera.width);
    EXPECT_EQ(back.height, camera.height);
    EXPECT_EQ(back.camera_matrix, camera.camera_matrix);
    EXPECT_EQ(back.distortion_model, camera.distortion_model);
    EXPECT_EQ(back.distortion_coefficients, camera.distortion_coefficients);
    EXPECT_EQ(back.rectification_matrix, camera.rectification_matrix);
    EXPECT_EQ(back.projection_matrix, camera.projection_matrix);
  }
}

TEST(CameraYaml, WritesTheSameBytesTwice) {
  test::TempDir dir;
  const CameraInfo camera = CameraInfo::ideal("left", 640, 480, 500.0, 320.0, 240.0);
  write_camera_info(dir.file("a.yaml"), camera);
  write_camera_info(dir.file("b.yaml"), camera);
  EXPECT_EQ(test::read_bytes(dir.file("a.yaml")), test::read_bytes(dir.file("b.yaml")));
  EXPECT_NE(test::read_bytes(dir.file("a.yaml")).find("data: [500, 0, 320, 0,"), std::string::npos)
      << test::read_bytes(dir.file("a.yaml"));
}

TEST(CameraYaml, AcceptsMinimalFileWithOnlySizeAndProjection) {
  test::TempDir dir;
  test::write_text(dir.file("c.yaml"),
                   "image_width: 640\nimage_height: 480\nprojection_matrix:\n  rows: 3\n  cols: 4\n"
                   "  data: [500, 0, 320, 0, 0, 500, 240, 0, 0, 0, 1, 0]\n");
  const CameraInfo camera = read_camera_info(dir.file("c.yaml"));
  EXPECT_EQ(camera.camera_name, "");
  EXPECT_TRUE(camera.distortion_coefficients.empty());
  EXPECT_EQ(camera.camera_matrix(0, 0), 500.0);  // taken from P
  EXPECT_EQ(camera.rectification_matrix, Eigen::Matrix3d::Identity());
}

struct BadCamera {
  const char* name;
  std::string text;
  const char* words;
};

class CameraYamlBadInput : public ::testing::TestWithParam<BadCamera> {};

TEST_P(CameraYamlBadInput, ThrowsFileErrorNamingTheFile) {
  test::TempDir dir;
  const std::string path = dir.file("left.yaml");
  test::write_text(path, GetParam().text);
  EXPECT_FILE_ERROR(read_camera_info(path), path, GetParam().words);
}

std::string replaced(const std::string& from, const std::string& to) {
  std::string text = kRosLeft;
  text.replace(text.find(from), from.size(), to);
  return text;
}

INSTANTIATE_TEST_SUITE_P(
    Cases, CameraYamlBadInput,
    ::testing::Values(
        BadCamera{"Malformed", "image_width: [640\nimage_height: 4", "malformed YAML"},
        BadCamera{"NotAMap", "- 1\n- 2\n", "map"},
        BadCamera{"NoProjection", replaced("projection_matrix:", "projection_matrox:"),
                  "missing key projection_matrix"},
        BadCamera{
            "ProjectionIs3x3",
            replaced("  cols: 4\n  data: [ 650.0, 0, 500.0, 0, 0, 650.0, 380.0, 0, 0, 0, 1, 0]",
                     "  cols: 3\n  data: [ 650.0, 0, 500.0, 0, 650.0, 380.0, 0, 0, 1]"),
            "projection_matrix: expected 3x4"},
        BadCamera{"ProjectionShortData", replaced("380.0, 0, 0, 0, 1, 0]", "380.0, 0, 0, 0, 1]"),
                  "data has 11 values"},
        BadCamera{"ProjectionNotNumeric",
                  replaced("380.0, 0, 0, 0, 1, 0]", "380.0, 0, 0, 0, one, 0]"),
                  "is not a finite number"},
        BadCamera{"WidthZero", replaced("image_width: 1024", "image_width: 0"), "image_width"},
        BadCamera{"WidthFractional", replaced("image_width: 1024", "image_width: 1024.5"),
                  "image_width"},
        BadCamera{"HeightText", replaced("image_height: 768", "image_height: tall"),
                  "image_height"},
        BadCamera{"NoHeight", replaced("image_height: 768\n", ""), "missing key image_height"},
        BadCamera{"CameraMatrix2x2",
                  replaced("  rows: 3\n  cols: 3\n  data: [ 704.5",
                           "  rows: 2\n  cols: 2\n  data: [ 704.5"),
                  "camera_matrix"}),
    [](const auto& info) { return std::string(info.param.name); });

TEST(CameraYaml, MissingFileIsFileError) {
  test::TempDir dir;
  EXPECT_FILE_ERROR(read_camera_info(dir.file("nope.yaml")), dir.file("nope.yaml"), "missing file");
}

TEST(StereoCameraYaml, ReadsRectifiedPairWithBaseline) {
  test::TempDir dir;
  test::write_text(dir.file("left.yaml"), kRosLeft);
  test::write_text(dir.file("right.yaml"), right_of(kRosLeft, "-78.0"));
  const StereoCamera cameras = read_stereo_camera(dir.file("left.yaml"), dir.file("right.yaml"));
  EXPECT_DOUBLE_EQ(cameras.baseline(), 0.12);
}

TEST(StereoCameraYaml, RejectsPairsThatAreNotRectified) {
  test::TempDir dir;
  const std::string left = dir.file("left.yaml"), right = dir.file("right.yaml");
  test::write_text(left, kRosLeft);

  test::write_text(right, right_of(kRosLeft, "78.0"));  // negative baseline: swapped files?
  EXPECT_FILE_ERROR(read_stereo_camera(left, right), right, "baseline");
  test::write_text(right, right_of(kRosLeft, "0"));
  EXPECT_FILE_ERROR(read_stereo_camera(left, right), right, "baseline");

  std::string other_size = right_of(kRosLeft, "-78.0");
  other_size.replace(other_size.find("image_width: 1024"), 17, "image_width: 1023");
  test::write_text(right, other_size);
  EXPECT_FILE_ERROR(read_stereo_camera(left, right), right, "1023x768");

  std::string other_fx = right_of(kRosLeft, "-78.0");
  other_fx.replace(other_fx.find("[ 650.0, 0, 500.0, -78.0"), 5, "[ 651");
  test::write_text(right, other_fx);
  EXPECT_FILE_ERROR(read_stereo_camera(left, right), right, "fx");

  test::write_text(right, right_of(kRosLeft, "-78.0"));
  test::write_text(left, right_of(kRosLeft, "-10.0"));  // left must carry no baseline
  EXPECT_FILE_ERROR(read_stereo_camera(left, right), left, "P[0][3]");

  EXPECT_FILE_ERROR(read_stereo_camera(dir.file("none.yaml"), right), dir.file("none.yaml"));
}

// Raw images: the pair's K, D and R must be able to build rectification maps,
// and P must still be a rectified pair (the images it produces).
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

class RawPair : public ::testing::Test {
 protected:
  void write(const std::string& left_text, const std::string& right_text) {
    test::write_text(left, left_text);
    test::write_text(right, right_text);
  }
  StereoCamera read() { return read_stereo_camera(left, right, ImageKind::Raw); }

  test::TempDir dir;
  const std::string left = dir.file("left.yaml"), right = dir.file("right.yaml");
  const std::string right_text = right_of(kRosLeft, "-78.0");
};

TEST_F(RawPair, ReadsAPairWithDistortionAndRotation) {
  const std::string rotated = replaced(kRosLeft, "data: [ 1, 0, 0, 0, 1, 0, 0, 0, 1]",
                                       "data: [ 0.99995, 0, 0.0099998, 0, 1, 0, -0.0099998, 0, 0.99995]");
  write(rotated, right_text);
  const StereoCamera cameras = read();
  EXPECT_EQ(cameras.images, ImageKind::Raw);
  EXPECT_DOUBLE_EQ(cameras.baseline(), 0.12);
  EXPECT_NEAR(cameras.left.rectification_matrix(0, 2), 0.0099998, 1e-12);
  // The same files declared rectified are read too (P is all that counts).
  EXPECT_EQ(read_stereo_camera(left, right).images, ImageKind::Rectified);
}

TEST_F(RawPair, AcceptsTheDistortionLengthsOfEachModel) {
  for (const char* data : {"rows: 1\n  cols: 4\n  data: [-0.1, 0.01, 0.0001, -0.0002]",
                           "rows: 1\n  cols: 8\n  data: [-0.1, 0.01, 0, 0, 0, 0, 0, 0]"}) {
    write(replaced(kRosLeft, "rows: 1\n  cols: 5\n  data: [-0.1, 0.01, 0.0001, -0.0002, 0]", data),
          right_text);
    EXPECT_NO_THROW(read()) << data;
  }
  const std::string fisheye =
      replaced(replaced(kRosLeft, "distortion_model: plumb_bob", "distortion_model: equidistant"),
               "rows: 1\n  cols: 5\n  data: [-0.1, 0.01, 0.0001, -0.0002, 0]",
               "rows: 1\n  cols: 4\n  data: [0.05, -0.01, 0.002, 0]");
  write(fisheye, right_text);
  EXPECT_NO_THROW(read());
}

TEST_F(RawPair, DistortionThatDoesNotFitItsModelNamesFileAndModel) {
  write(replaced(kRosLeft, "rows: 1\n  cols: 5\n  data: [-0.1, 0.01, 0.0001, -0.0002, 0]",
                 "rows: 1\n  cols: 6\n  data: [-0.1, 0.01, 0.0001, -0.0002, 0, 0]"),
        right_text);
  EXPECT_FILE_ERROR(read(), left, "6 distortion_coefficients do not fit distortion_model plumb_bob");
  write(replaced(kRosLeft, "distortion_model: plumb_bob", "distortion_model: equidistant"),
        right_text);
  EXPECT_FILE_ERROR(read(), left, "5 distortion_coefficients do not fit distortion_model equidistant");
  write(kRosLeft, replaced(right_text, "distortion_model: plumb_bob", "distortion_model: fov"));
  EXPECT_FILE_ERROR(read(), right, "distortion_model 'fov' is not supported");
  write(replaced(kRosLeft, "rows: 1\n  cols: 5\n  data: [-0.1, 0.01, 0.0001, -0.0002, 0]",
                 "rows: 1\n  cols: 0\n  data: []"),
        right_text);
  EXPECT_FILE_ERROR(read(), left, "0 distortion_coefficients");
}

TEST_F(RawPair, CameraMatrixMustBeSane) {
  write(replaced(kRosLeft, "data: [ 704.5, 0, 512.25", "data: [ -704.5, 0, 512.25"), right_text);
  EXPECT_FILE_ERROR(read(), left, "camera_matrix: fx and fy must be positive");
  write(kRosLeft, replaced(right_text, "0, 704.5, 384.75, 0, 0, 1]", "0, 704.5, 384.75, 0, 0, 2]"));
  EXPECT_FILE_ERROR(read(), right, "camera_matrix: expected");
  write(replaced(kRosLeft, "data: [ 704.5, 0, 512.25", "data: [ 704.5, 0, 1512.25"), right_text);
  EXPECT_FILE_ERROR(read(), left, "principal point (1512.25, 384.75) lies outside the 1024x768");
}

TEST_F(RawPair, RectificationMatrixMustBeARotation) {
  write(replaced(kRosLeft, "data: [ 1, 0, 0, 0, 1, 0, 0, 0, 1]", "data: [ 1, 0, 0, 0, 1, 0, 0, 0, 2]"),
        right_text);
  EXPECT_FILE_ERROR(read(), left, "rectification_matrix is not a rotation");
  write(kRosLeft,
        replaced(right_text, "data: [ 1, 0, 0, 0, 1, 0, 0, 0, 1]", "data: [ 1, 0, 0, 0, 1, 0, 0, 0, -1]"));
  EXPECT_FILE_ERROR(read(), right, "rectification_matrix is not a rotation");
}

TEST_F(RawPair, SizesAndProjectionsMustFormAPair) {
  write(kRosLeft, replaced(right_text, "image_width: 1024", "image_width: 1280"));
  EXPECT_FILE_ERROR(read(), right, "image size 1280x768 differs");
  write(kRosLeft, right_of(kRosLeft, "78.0"));
  EXPECT_FILE_ERROR(read(), right, "baseline");
}

}  // namespace
}  // namespace l2s::io
