// The Calibrator on bad frames: frames without the board, one hole occluded, a
// cloud without `ring`, shuffled point order, NaN points, an empty sweep. Bad
// frames are skipped with a reason, nothing throws, and the result stays
// correct when enough good frames remain.

#include <l2s/calibrator.hpp>
#include <l2s/error.hpp>
#include <l2s/metrics.hpp>
#include <l2s/sim/simulation.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

namespace {

using l2s::Calibrator;
using l2s::sim::DatasetSimulator;
using l2s::sim::SimulationConfig;

constexpr int kFrames = 6;

SimulationConfig setting_one() {
  auto config = SimulationConfig::paper(1, "vlp16");
  config.frames = kFrames;
  config.seed = 77;
  return config;
}

// One simulation shared by the cases: the expensive render happens once.
const DatasetSimulator& simulator() {
  static const DatasetSimulator instance(setting_one());
  return instance;
}

Calibrator make_calibrator() {
  return Calibrator(simulator().cameras(), simulator().config().target, Calibrator::Params::preset("default"));
}

double max_center_distance(const l2s::HoleCenters& a, const l2s::HoleCenters& b) {
  double worst = 0.0;
  for (int i = 0; i < 4; ++i) worst = std::max(worst, (a[i] - b[i]).norm());
  return worst;
}

TEST(CalibratorRobustness, EmptySweepIsSkippedWithReason) {
  auto calibrator = make_calibrator();
  const auto frame = simulator().frame(0);
  const auto report = calibrator.add(l2s::LidarCloud{}, frame.left, frame.right, "empty");
  EXPECT_FALSE(report.lidar.found);
  EXPECT_EQ(report.lidar.failed_stage, "input");
  EXPECT_FALSE(report.lidar.reason.empty());
  EXPECT_TRUE(report.camera.found) << report.camera.reason;
  const auto result = calibrator.result();
  EXPECT_FALSE(result.found);
  EXPECT_NE(result.reason.find("lidar 0"), std::string::npos) << result.reason;
}

TEST(CalibratorRobustness, ShuffledNanAndRinglessSweepsGiveTheSameCentres) {
  auto calibrator = make_calibrator();
  const auto frame = simulator().frame(1);
  const auto reference = calibrator.add(frame.lidar, frame.left, frame.right, "reference");
  ASSERT_TRUE(reference.lidar.found) << reference.lidar.reason;

  l2s::LidarCloud shuffled = frame.lidar;
  std::vector<std::size_t> order(shuffled.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::shuffle(order.begin(), order.end(), std::mt19937_64(5));
  for (std::size_t i = 0; i < order.size(); ++i) {
    shuffled.points[i] = frame.lidar.points[order[i]];
    shuffled.ring[i] = frame.lidar.ring[order[i]];
    shuffled.intensity[i] = frame.lidar.intensity[order[i]];
  }
  // A NaN point after every tenth point: inserted, so no real data is lost.
  l2s::LidarCloud with_nan;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t i = 0; i < shuffled.size(); ++i) {
    with_nan.points.push_back(shuffled.points[i]);
    with_nan.ring.push_back(shuffled.ring[i]);
    with_nan.intensity.push_back(shuffled.intensity[i]);
    if (i % 10 == 0) {
      with_nan.points.emplace_back(nan, nan, nan);
      with_nan.ring.push_back(shuffled.ring[i]);
      with_nan.intensity.push_back(0.0f);
    }
  }
  const auto shuffled_report = calibrator.add(with_nan, frame.left, frame.right, "shuffled+nan");
  ASSERT_TRUE(shuffled_report.lidar.found) << shuffled_report.lidar.reason;
  // RANSAC draws its samples by index, so order moves the result by noise only.
  EXPECT_LT(max_center_distance(shuffled_report.lidar.centers, reference.lidar.centers), 5e-4);

  l2s::LidarCloud ringless = frame.lidar;
  ringless.ring.clear();
  const auto ringless_report = calibrator.add(ringless, frame.left, frame.right, "ringless");
  ASSERT_TRUE(ringless_report.lidar.found) << ringless_report.lidar.reason;
  EXPECT_LT(max_center_distance(ringless_report.lidar.centers, reference.lidar.centers), 5e-4);
}

TEST(CalibratorRobustness, FramesWithoutTheBoardAreSkippedAndTheResultStaysCorrect) {
  auto calibrator = make_calibrator();
  // A blank, featureless pair and a sweep of only far returns: no board anywhere.
  const auto& cameras = simulator().cameras();
  const l2s::Image blank(cameras.left.width, cameras.left.height, 1, 128);
  for (int i = 0; i < kFrames; ++i) {
    const auto frame = simulator().frame(i);
    l2s::LidarCloud far_only;
    for (std::size_t k = 0; k < frame.lidar.size(); ++k)
      if (frame.lidar.points[k].norm() > 5.0) {
        far_only.points.push_back(frame.lidar.points[k]);
        far_only.ring.push_back(frame.lidar.ring[k]);
      }
    const auto bad = calibrator.add(far_only, blank, blank, "bad" + std::to_string(i));
    EXPECT_FALSE(bad.lidar.found);
    EXPECT_FALSE(bad.camera.found);
    EXPECT_FALSE(bad.lidar.reason.empty());
    EXPECT_FALSE(bad.camera.reason.empty());
    calibrator.add(frame.lidar, frame.left, frame.right, "good" + std::to_string(i));
  }
  const auto result = calibrator.result();
  ASSERT_TRUE(result.found) << result.reason;
  EXPECT_EQ(result.frames_added, 2 * kFrames);
  EXPECT_EQ(result.lidar_frames, kFrames);
  const auto error = l2s::pose_error(result.T_lidar_camera, simulator().T_lidar_camera());
  EXPECT_LT(error.translation, 0.01);
  EXPECT_LT(error.rotation * 180.0 / M_PI, 0.3);  // six frames: the single-run bound
}

TEST(CalibratorRobustness, BoardWithOneHoleOccludedIsRejectedWithReason) {
  // A box floating just in front of the top-left hole hides it from both sensors.
  auto config = setting_one();
  config.frames = 2;
  config.board_pose = simulator().board_pose();
  config.strict_placement = false;
  const Eigen::Isometry3d T_cambody_board = config.board_pose->T_cambody_board();
  const Eigen::Vector2d hole = config.target.hole_centers()[static_cast<int>(l2s::Hole::TopLeft)];
  l2s::sim::Box occluder;
  occluder.T_cambody_box = T_cambody_board * Eigen::Translation3d(hole.x(), hole.y(), 0.3);
  occluder.half_size = Eigen::Vector3d(0.22, 0.22, 0.05);
  config.layout.extra_clutter.push_back(occluder);
  const DatasetSimulator occluded(config);

  auto calibrator = make_calibrator();
  for (int i = 0; i < config.frames; ++i) {
    const auto frame = occluded.frame(i);
    const auto report = calibrator.add(frame.lidar, frame.left, frame.right);
    EXPECT_FALSE(report.lidar.found) << "lidar found four holes with one occluded";
    EXPECT_FALSE(report.camera.found) << "camera found four holes with one occluded";
    EXPECT_FALSE(report.lidar.reason.empty());
    EXPECT_FALSE(report.camera.reason.empty());
  }
  EXPECT_FALSE(calibrator.result().found);
}

TEST(CalibratorRobustness, ARingFreeRecordingShorterThanOneWindowStillCalibrates) {
  // A Livox Avia recording of 8 sweeps, less than ring_free_frames (20): the
  // window left open is detected when the result is asked for.
  auto config = l2s::sim::SimulationConfig::paper(1, "avia");
  config.frames = 8;
  config.seed = 78;
  const DatasetSimulator avia(config);
  Calibrator calibrator(avia.cameras(), avia.config().target, Calibrator::Params::preset("default"));
  ASSERT_GT(calibrator.params().ring_free_frames, config.frames);
  const auto first = avia.frame(0);
  const l2s::BranchReport camera = calibrator.camera_branch(first.left, first.right);
  ASSERT_TRUE(camera.found) << camera.reason;
  for (int i = 0; i < config.frames; ++i) {
    const auto report = calibrator.add(avia.sweep(i), camera);
    EXPECT_FALSE(report.lidar.found);  // still accumulating
  }
  const auto result = calibrator.result();
  EXPECT_EQ(result.lidar_frames, 1);
  ASSERT_TRUE(result.found) << result.reason;
  const auto error = l2s::pose_error(result.T_lidar_camera, avia.T_lidar_camera());
  EXPECT_LT(error.translation, 0.02);
  EXPECT_LT(error.rotation, 0.5 * M_PI / 180.0);
}

TEST(CalibratorRobustness, ImagesOfTheWrongSizeThrowParamError) {
  auto calibrator = make_calibrator();
  const auto frame = simulator().frame(0);
  const l2s::Image small(64, 48, 1, 0);
  EXPECT_THROW(calibrator.add(frame.lidar, small, small), l2s::ParamError);
}

}  // namespace
