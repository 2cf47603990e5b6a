// LidarPairCalibrator on simulated lidar-lidar recordings (issue 9, "Lidar to
// lidar"): the acceptance figure (VLP-16 to HDL-32E, three poses, median over
// settings), a ring-free second lidar, moving frames kept out of the poses.
#include <l2s/lidar_pair_calibrator.hpp>
#include <l2s/metrics.hpp>
#include <l2s/sim/lidar_pair.hpp>

#include "support/test_data.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace l2s {
namespace {

struct PairRun {
  LidarPairCalibrator::Result result;
  PoseError error;
  std::vector<int> moving_frames;  ///< the simulator's
};

sim::LidarPairConfig config(const std::string& lidar, const std::string& lidar2, int poses, int frames,
                            std::uint64_t seed, int setting = 1) {
  sim::LidarPairConfig c;
  c.base = sim::SimulationConfig::paper(setting, lidar);
  c.base.frames = frames;
  c.base.seed = seed;
  c.base.threads = 2;
  c.lidar2 = lidar2;
  c.poses = poses;
  return c;
}

PairRun calibrate(const sim::LidarPairConfig& c) {
  const sim::LidarPairSimulator simulator(c);
  LidarPairCalibrator calibrator(c.base.target);
  for (int i = 0; i < simulator.frames(); ++i) {
    const sim::SimulatedFrame frame = simulator.frame(i);
    calibrator.add(frame.lidar, frame.lidar2);
  }
  PairRun run;
  run.result = calibrator.result();
  run.error = pose_error(run.result.T_lidar_lidar2, simulator.T_lidar_lidar2());
  run.moving_frames = simulator.moving_frames();
  return run;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

// Issue 9's acceptance: VLP-16 to HDL-32E, 3 poses of 10 frames, median
// <= 2 mm / 0.05 deg. The median is over three of the paper's settings, one
// of each row of Table I (each its own board poses, lidar2 mount and noise).
TEST(LidarPairCalibrator, Vlp16ToHdl32ThreePosesMeetsAcceptance) {
  std::vector<double> e_t, e_r;
  for (int setting : {1, 4, 7}) {
    const PairRun run = calibrate(config("vlp16", "hdl32", 3, 10, 1, setting));
    ASSERT_TRUE(run.result.found) << "setting " << setting << ": " << run.result.reason;
    EXPECT_EQ(run.result.poses_used(), 3) << "setting " << setting;
    EXPECT_EQ(run.result.check.verdict, CalibrationCheck::Verdict::Ok) << "setting " << setting;
    for (const LidarPairPoseReport& pose : run.result.poses)
      for (int f : pose.frames)
        EXPECT_EQ(std::count(run.moving_frames.begin(), run.moving_frames.end(), f), 0)
            << "setting " << setting << ": moving frame " << f << " in a pose";
    e_t.push_back(run.error.translation);
    e_r.push_back(run.error.rotation * 180.0 / M_PI);
  }
  EXPECT_LE(median(e_t), 0.002);
  EXPECT_LE(median(e_r), 0.05);
}

// One pose: no residual shows what each lidar's detection of the pose shares
// across its four centres (the plane's tilt, the pattern's turn in it), so
// the stated 95 % bound must hold both lidars' share, not one. With one
// share the bounds held all six DoFs in 4 of 9 one-pose runs of the suite's
// lidar-pair experiment (seed 1); with both, in 24 of 27 (three seeds).
TEST(LidarPairCalibrator, OnePoseBoundHoldsBothLidarsShare) {
  const PairRun run = calibrate(config("vlp16", "hdl32", 1, 10, 1, 4));
  ASSERT_TRUE(run.result.found) << run.result.reason;
  const FitUncertainty& u = run.result.joint.uncertainty;
  ASSERT_TRUE(u.valid);
  const JointRegistrar::Params joint = Calibrator::Params::preset("default").joint;
  for (int k = 3; k < 6; ++k)
    EXPECT_GE(u.bound_95[k], 1.96 * std::sqrt(2.0) * joint.pose_bias_rotation) << "rotation DoF " << k - 3;
  for (int k = 0; k < 3; ++k)
    EXPECT_GE(u.bound_95[k], 1.96 * std::sqrt(2.0) * joint.pose_bias_translation) << "translation DoF " << k;
  EXPECT_LE(run.error.rotation, std::hypot(u.bound_95[3], u.bound_95[4], u.bound_95[5]));
}

// A ring-free lidar2 (Livox Avia): its sweeps are accumulated over the static
// board (one detection per 20 sweeps) against the VLP-16's every sweep.
TEST(LidarPairCalibrator, RingFreeLidar2IsAccumulated) {
  const PairRun run = calibrate(config("vlp16", "avia", 1, 20, 4));
  ASSERT_TRUE(run.result.found) << run.result.reason;
  EXPECT_EQ(run.result.lidar2_frames, 1);
  EXPECT_GE(run.result.lidar_frames, 15);
  EXPECT_LE(run.error.translation, 0.01);
  EXPECT_LE(run.error.rotation * 180.0 / M_PI, 0.3);
}

// A ring-free lidar2 over several poses: the VLP-16 sees the board move, and
// that closes the Avia's window, so no window straddles a move and every pose
// gets its own ring-free detection (before, windows of 20 sweeps ran on over
// the moving frames: a Mid-360 recording lost a pose and was 1 cm off).
TEST(LidarPairCalibrator, RingFreeWindowsFollowTheBoardPoses) {
  const PairRun run = calibrate(config("vlp16", "avia", 3, 20, 1));
  ASSERT_TRUE(run.result.found) << run.result.reason;
  EXPECT_EQ(run.result.poses_used(), 3);
  EXPECT_EQ(run.result.lidar2_frames, 3);
  EXPECT_LE(run.error.translation, 0.008);
  EXPECT_LE(run.error.rotation * 180.0 / M_PI, 0.15);
}

// Without detections there is no transform: a status with a reason, no throw.
TEST(LidarPairCalibrator, EmptySweepsFailWithAReason) {
  LidarPairCalibrator calibrator{Target{}};
  for (int i = 0; i < 3; ++i) calibrator.add(LidarCloud{}, LidarCloud{});
  const LidarPairCalibrator::Result result = calibrator.result();
  EXPECT_FALSE(result.found);
  EXPECT_NE(result.reason.find("lidar2 0 of 3"), std::string::npos) << result.reason;
  EXPECT_EQ(result.check.verdict, CalibrationCheck::Verdict::Failed);
  EXPECT_FALSE(result.frames[0].lidar2.reason.empty());
}

}  // namespace
}  // namespace l2s
