#include <l2s/error.hpp>
#include <l2s/io/calibrator_yaml.hpp>
#include <l2s/io/transform_yaml.hpp>

#include "support/test_data.hpp"

#include <gtest/gtest.h>

namespace {

using l2s::Calibrator;

TEST(CalibratorParamsYaml, RoundTripsEveryPreset) {
  l2s::test::TempDir dir;
  for (const char* preset : {"default", "paper"}) {
    const auto params = Calibrator::Params::preset(preset);
    const std::string path = dir.file(std::string(preset) + ".yaml");
    l2s::io::write_calibrator_params(path, params);
    const auto read = l2s::io::read_calibrator_params(path);
    // Written again, the file must not change: every field survived.
    const std::string again = dir.file(std::string(preset) + "_again.yaml");
    l2s::io::write_calibrator_params(again, read);
    EXPECT_EQ(l2s::test::read_bytes(path), l2s::test::read_bytes(again)) << preset;
    EXPECT_EQ(read.discontinuity.placement, params.discontinuity.placement);
    EXPECT_EQ(read.accumulator.estimator, params.accumulator.estimator);
    EXPECT_EQ(read.refine_camera_pose, params.refine_camera_pose);
    EXPECT_EQ(read.lidar_pass_through.min_xyz, params.lidar_pass_through.min_xyz);  // infinities
  }
}

// One default: a user who writes Params{} gets what the tools call "default"
// (every field, compared through the file that lists them all).
TEST(CalibratorParamsYaml, DefaultConstructedParamsAreTheDefaultPreset) {
  l2s::test::TempDir dir;
  l2s::io::write_calibrator_params(dir.file("constructed.yaml"), Calibrator::Params{});
  l2s::io::write_calibrator_params(dir.file("preset.yaml"), Calibrator::Params::preset("default"));
  l2s::io::write_calibrator_params(dir.file("paper.yaml"), Calibrator::Params::preset("paper"));
  const std::string constructed = l2s::test::read_bytes(dir.file("constructed.yaml"));
  EXPECT_EQ(constructed, l2s::test::read_bytes(dir.file("preset.yaml")));
  EXPECT_NE(constructed, l2s::test::read_bytes(dir.file("paper.yaml")));
}

TEST(CalibratorParamsYaml, OverridesOnTopOfThePreset) {
  l2s::test::TempDir dir;
  l2s::test::write_text(dir.file("p.yaml"), "preset: paper\nedges:\n  sobel_threshold: 90\naccumulator:\n  min_frames: 5\n");
  const auto params = l2s::io::read_calibrator_params(dir.file("p.yaml"));
  EXPECT_DOUBLE_EQ(params.edges.sobel_threshold, 90.0);
  EXPECT_EQ(params.accumulator.min_frames, 5);
  EXPECT_FALSE(params.refine_camera_pose);  // from the paper preset
}

void expect_file_error(const std::string& path, const std::string& content, const std::string& words) {
  l2s::test::write_text(path, content);
  try {
    l2s::io::read_calibrator_params(path);
    FAIL() << "accepted: " << content;
  } catch (const l2s::FileError& error) {
    EXPECT_EQ(error.path(), path);
    EXPECT_NE(std::string(error.what()).find(words), std::string::npos) << error.what();
  }
}

TEST(CalibratorParamsYaml, RejectsTyposBadValuesAndInvalidParams) {
  l2s::test::TempDir dir;
  const std::string path = dir.file("bad.yaml");
  expect_file_error(path, "edges:\n  sobel_treshold: 100\n", "unknown key edges.sobel_treshold");
  expect_file_error(path, "accumulator:\n  min_frames: many\n", "accumulator.min_frames");
  expect_file_error(path, "discontinuity:\n  placement: middle\n", "placement");
  expect_file_error(path, "lidar_plane:\n  max_angle: -1\n", "lidar_plane.max_angle");
  expect_file_error(path, "preset: fancy\n", "fancy");
  expect_file_error(path, "[1, 2]\n", "mapping");
}

TEST(CalibrationResultYaml, HoldsTheTransformAndItsInverse) {
  l2s::test::TempDir dir;
  Calibrator::Result result;
  result.found = true;
  result.T_lidar_camera.linear() =
      Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  result.T_lidar_camera.translation() = Eigen::Vector3d(0.8, 0.1, -0.4);
  const std::string path = dir.file("result.yaml");
  l2s::io::write_calibration_result(path, result, "some/dataset", "default");
  EXPECT_POSE_NEAR(l2s::io::read_transform(path), result.T_lidar_camera, 1e-9, 1e-12);
  EXPECT_POSE_NEAR(l2s::io::read_transform(path, "T_camera_lidar"), result.T_lidar_camera.inverse(), 1e-9, 1e-12);
}

}  // namespace
