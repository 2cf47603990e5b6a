#include <l2s/error.hpp>
#include <l2s/io/calibrator_yaml.hpp>
#include <l2s/io/transform_yaml.hpp>
#include <l2s/joint_registrar.hpp>
#include <l2s/pose.hpp>

#include "support/test_data.hpp"

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cmath>

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
  // A key that is itself a mapping (found by fuzzing: it threw yaml-cpp's bad conversion).
  expect_file_error(path, "registrar:\n  {}:\n  {}\n", "a key of registrar. is not a name");
  expect_file_error(path, "{}: 1\n", "a key of the file is not a name");
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

TEST(CalibrationResultYaml, RoundTripsPosesUncertaintyAndLeaveOneOut) {
  // Three poses of exact centres with a little deterministic noise, the second rejected as far off.
  const Eigen::Isometry3d T = l2s::pose_from_roll_pitch_yaw(-1.5, 0.02, -1.6, {-0.4, 0.1, -0.2});
  std::vector<l2s::PosePair> pairs;
  int k = 0;
  for (const Eigen::Vector3d& c : {Eigen::Vector3d(3, 0.5, 0), Eigen::Vector3d(4, -1, 0.2), Eigen::Vector3d(2.5, 0, -0.3),
                                   Eigen::Vector3d(3.5, 1, 0.1)}) {
    l2s::PosePair pair;
    for (int h = 0; h < 4; ++h) {
      pair.target[h] = c + Eigen::Vector3d(0.0, h % 2 ? -0.25 : 0.25, h < 2 ? 0.2 : -0.2);
      pair.source[h] = T.inverse() * pair.target[h] + Eigen::Vector3d::Constant(0.002 * std::sin(++k));
      if (pairs.size() == 1) pair.source[h] += Eigen::Vector3d(0.1, 0, 0);
    }
    pairs.push_back(pair);
  }
  Calibrator::Result result;
  result.found = true;
  result.joint = l2s::JointRegistrar().estimate(pairs);
  ASSERT_TRUE(result.joint.found && result.joint.uncertainty.valid);
  ASSERT_EQ(result.joint.used_count(), 3);
  result.T_lidar_camera = result.joint.T_target_source;
  for (int p = 0; p < 4; ++p) {
    l2s::PoseReport pose;
    pose.first_frame = 10 * p;
    pose.last_frame = 10 * p + 7;
    pose.frames = {10 * p, 10 * p + 7};
    pose.used = result.joint.used[p];
    pose.rms = result.joint.pose_rms[p];
    if (!pose.used) pose.reason = "rejected";
    result.poses.push_back(pose);
  }
  result.moving_frames = {8, 9, 18};
  l2s::test::TempDir dir;
  const std::string path = dir.file("result.yaml");
  l2s::io::write_calibration_result(path, result);

  const YAML::Node yaml = YAML::LoadFile(path);
  EXPECT_EQ(yaml["poses"]["found"].as<int>(), 4);
  EXPECT_EQ(yaml["poses"]["used"].as<int>(), 3);
  EXPECT_EQ(yaml["poses"]["moving_frames"].as<std::vector<int>>(), result.moving_frames);
  EXPECT_FALSE(yaml["poses"]["list"][1]["used"].as<bool>());
  EXPECT_EQ(yaml["poses"]["list"][1]["reason"].as<std::string>(), "rejected");
  EXPECT_EQ(yaml["poses"]["list"][2]["first_frame"].as<int>(), 20);
  EXPECT_NEAR(yaml["poses"]["list"][3]["rms_m"].as<double>(), result.joint.pose_rms[3], 1e-12);
  const l2s::FitUncertainty& u = result.joint.uncertainty;
  for (int d = 0; d < 6; ++d) {
    const double unit = d < 3 ? 1.0 : 180.0 / M_PI;
    const std::string key = std::string(l2s::dof_names()[d]) + (d < 3 ? "_m" : "_deg");
    EXPECT_NEAR(yaml["uncertainty"]["sigma"][key].as<double>(), u.sigma[d] * unit, 1e-9 * unit) << key;
    EXPECT_NEAR(yaml["uncertainty"]["bound_95"][key].as<double>(), u.bound_95[d] * unit, 1e-9 * unit) << key;
  }
  EXPECT_EQ(yaml["uncertainty"]["dof"].as<int>(), u.dof);
  EXPECT_NEAR(yaml["uncertainty"]["condition"].as<double>(), u.condition, 1e-9 * u.condition);
  const YAML::Node loo = yaml["leave_one_pose_out"];
  ASSERT_EQ(loo.size(), 3u);
  EXPECT_EQ(loo[1]["pose"].as<int>(), 2);  // pose 1 was rejected: not left out, never in
  EXPECT_NEAR(loo[1]["translation_m"].as<double>(), result.joint.leave_one_out[1].translation, 1e-12);
  EXPECT_NEAR(loo[2]["rotation_deg"].as<double>(), result.joint.leave_one_out[2].rotation * 180 / M_PI, 1e-9);
  // The DATASET.md key is still first and unchanged.
  EXPECT_POSE_NEAR(l2s::io::read_transform(path), result.T_lidar_camera, 1e-9, 1e-12);
}

}  // namespace
