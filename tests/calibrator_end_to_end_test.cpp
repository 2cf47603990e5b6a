// End to end on the simulated suite: each of the paper's nine settings with a
// VLP-16 at noise K = 1, both presets, accuracy checked against ground truth,
// and the scene check's verdict on them and on transforms 1 deg / 2 cm off.

#include <l2s/calibrator.hpp>
#include <l2s/metrics.hpp>
#include <l2s/sim/simulation.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace {

constexpr int kFrames = 30;
// Bounds of the default preset, with margin over what it measures (README).
constexpr double kMaxTranslationError = 0.008;  // [m]
constexpr double kMaxRotationErrorDeg = 0.20;   // [deg]

class CalibratorEndToEnd : public ::testing::TestWithParam<int> {};

TEST_P(CalibratorEndToEnd, BothPresetsSucceedAndDefaultIsAccurate) {
  auto config = l2s::sim::SimulationConfig::paper(GetParam(), "vlp16");
  config.frames = kFrames;
  config.noise_factor = 1.0;
  config.seed = 1000 + GetParam();
  const l2s::sim::DatasetSimulator simulator(config);
  const Eigen::Isometry3d truth = simulator.T_lidar_camera();

  l2s::Calibrator tuned(simulator.cameras(), config.target, l2s::Calibrator::Params::preset("default"));
  l2s::Calibrator paper(simulator.cameras(), config.target, l2s::Calibrator::Params::preset("paper"));
  for (int i = 0; i < kFrames; ++i) {
    const auto frame = simulator.frame(i);
    tuned.add(frame.lidar, frame.left, frame.right);
    paper.add(frame.lidar, frame.left, frame.right);
  }

  const auto tuned_result = tuned.result();
  const auto paper_result = paper.result();
  ASSERT_TRUE(tuned_result.found) << tuned_result.reason;
  ASSERT_TRUE(paper_result.found) << paper_result.reason;

  const auto tuned_error = l2s::pose_error(tuned_result.T_lidar_camera, truth);
  const auto paper_error = l2s::pose_error(paper_result.T_lidar_camera, truth);
  std::printf("setting %d: default e_t %.1f mm e_r %.3f deg (%d/%d frames) | paper e_t %.1f mm e_r %.3f deg\n",
              GetParam(), tuned_error.translation * 1e3, tuned_error.rotation * 180 / M_PI,
              tuned_result.lidar_frames, tuned_result.camera_frames, paper_error.translation * 1e3,
              paper_error.rotation * 180 / M_PI);
  EXPECT_LE(tuned_error.translation, kMaxTranslationError);
  EXPECT_LE(tuned_error.rotation * 180 / M_PI, kMaxRotationErrorDeg);

  // The scene check (issue 11): good results are ok ...
  EXPECT_EQ(tuned_result.quality.verdict, l2s::CalibrationCheck::Verdict::Ok) << describe(tuned_result.quality);
  if (paper_error.translation <= 0.02 && paper_error.rotation <= 0.5 * M_PI / 180) {
    EXPECT_EQ(paper_result.quality.verdict, l2s::CalibrationCheck::Verdict::Ok) << describe(paper_result.quality);
  }
  // ... and a transform 1 deg (about each camera axis) and 2 cm off is reported off.
  const l2s::CalibrationCheck check(simulator.cameras(), config.target, tuned.params().check);
  for (int axis = 0; axis < 3; ++axis) {
    Eigen::Isometry3d wrong = truth;
    wrong.linear() = truth.linear() * Eigen::AngleAxisd(M_PI / 180, Eigen::Vector3d::Unit(axis)).toRotationMatrix();
    wrong.translation() += 0.02 * (truth.linear() * Eigen::Vector3d::Unit((axis + 2) % 3));
    const auto report = check.check(tuned.check_frames(), wrong);
    EXPECT_NE(report.verdict, l2s::CalibrationCheck::Verdict::Ok) << "axis " << axis << "\n" << describe(report);
  }
}

INSTANTIATE_TEST_SUITE_P(PaperSettings, CalibratorEndToEnd, ::testing::Range(1, 10),
                         [](const auto& info) { return "Setting" + std::to_string(info.param); });

}  // namespace

namespace {

// Dense lidars on the settings where the board's top holes reach past the
// HDL-64E's +2 deg top beam and the board plane meets the ground: the plane
// must still be the board, and the clipped holes still form the pattern.
class CalibratorDenseLidar : public ::testing::TestWithParam<int> {};

TEST_P(CalibratorDenseLidar, Hdl64FindsTheBoardAndCalibrates) {
  auto config = l2s::sim::SimulationConfig::paper(GetParam(), "hdl64");
  config.frames = 5;
  config.seed = 2000 + GetParam();
  const l2s::sim::DatasetSimulator simulator(config);
  l2s::Calibrator calibrator(simulator.cameras(), config.target, l2s::Calibrator::Params::preset("default"));
  for (int i = 0; i < config.frames; ++i) {
    const auto frame = simulator.frame(i);
    calibrator.add(frame.lidar, frame.left, frame.right);
  }
  const auto result = calibrator.result();
  ASSERT_TRUE(result.found) << result.reason;
  EXPECT_EQ(result.lidar_frames, config.frames);
  const auto error = l2s::pose_error(result.T_lidar_camera, simulator.T_lidar_camera());
  std::printf("hdl64 setting %d: e_t %.1f mm e_r %.3f deg\n", GetParam(), error.translation * 1e3,
              error.rotation * 180 / M_PI);
  EXPECT_LE(error.translation, 0.02);
  EXPECT_LE(error.rotation * 180 / M_PI, 0.3);
}

INSTANTIATE_TEST_SUITE_P(ClippedBoards, CalibratorDenseLidar, ::testing::Values(3, 6),
                         [](const auto& info) { return "Setting" + std::to_string(info.param); });

}  // namespace
