// Multi-pose recordings (issue 9): the simulator's poses and moving frames,
// and the Calibrator grouping them (a moving frame never enters a pose).

#include <l2s/sim/multi_pose.hpp>

#include <l2s/calibrator.hpp>
#include <l2s/error.hpp>
#include <l2s/io/dataset.hpp>
#include <l2s/metrics.hpp>

#include "support/test_data.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

namespace l2s::sim {
namespace {

MultiPoseConfig two_poses() {
  MultiPoseConfig config;
  config.base = SimulationConfig::paper(8, "vlp16");
  config.base.frames = 3;
  config.base.seed = 5;
  config.poses = 2;
  config.moving_frames = 2;
  return config;
}

// One simulator for every test of the file: the placement searches and the
// renders of its stretches are most of the time.
const MultiPoseSimulator& shared() {
  static const MultiPoseSimulator simulator(two_poses());
  return simulator;
}

TEST(MultiPoseSimulator, PosesAreSpreadAndMovingFramesLieBetween) {
  const MultiPoseSimulator& simulator = shared();
  ASSERT_EQ(simulator.poses().size(), 2u);
  EXPECT_EQ(simulator.frames(), 8);
  EXPECT_EQ(simulator.moving_frames(), (std::vector<int>{3, 4}));
  const BoardPose a = simulator.poses()[0], b = simulator.poses()[1];
  EXPECT_GT(std::hypot(a.x - b.x, a.y - b.y), 0.4);  // far beyond the grouping tolerance
  // The spread is a prefix family: the first of two is the first of one.
  const std::vector<BoardPose> one = find_pose_spread(two_poses().base, 1);
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(one[0].x, a.x);
  EXPECT_EQ(one[0].y, a.y);
  EXPECT_THROW(find_pose_spread(two_poses().base, 6), ParamError);
}

TEST(MultiPoseSimulator, CalibratorSkipsTheMovingFramesAndFitsBothPoses) {
  const MultiPoseSimulator& simulator = shared();
  Calibrator::Params params;
  params.check_result = false;  // the check is tested elsewhere; this is about poses
  params.poses.min_frames = 2;
  Calibrator calibrator(simulator.cameras(), simulator.config().base.target, params);
  for (int i = 0; i < simulator.frames(); ++i) {
    const SimulatedFrame frame = simulator.frame(i);
    calibrator.add(frame.lidar, frame.left, frame.right);
  }
  const Calibrator::Result result = calibrator.result();
  ASSERT_TRUE(result.found) << result.reason;
  ASSERT_EQ(result.poses.size(), 2u);
  EXPECT_EQ(result.poses_used(), 2) << result.poses[0].reason << " / " << result.poses[1].reason;
  const std::vector<int> moving = simulator.moving_frames();
  for (const PoseReport& pose : result.poses)
    for (int f : pose.frames) EXPECT_EQ(std::count(moving.begin(), moving.end(), f), 0) << "frame " << f;
  for (int f : result.moving_frames) EXPECT_EQ(std::count(moving.begin(), moving.end(), f), 1) << "frame " << f;
  EXPECT_EQ(result.joint.leave_one_out.size(), 2u);
  EXPECT_TRUE(result.joint.uncertainty.valid);
  const PoseError e = pose_error(result.T_lidar_camera, simulator.T_lidar_camera());
  EXPECT_LT(e.translation, 0.02);  // three frames per pose: a sanity bound, accuracy is the suite's
  EXPECT_LT(e.rotation, 0.5 * M_PI / 180.0);
}

TEST(MultiPoseSimulator, WritesADatasetWithItsPoses) {
  test::TempDir dir;
  shared().write(dir.file("multi"));
  const io::Dataset dataset = io::Dataset::open(dir.file("multi"));
  EXPECT_EQ(dataset.size(), 8u);
  EXPECT_TRUE(std::filesystem::exists(dir.file("multi/poses.yaml")));
  EXPECT_TRUE(dataset.ground_truth().has_value());
}

}  // namespace
}  // namespace l2s::sim
