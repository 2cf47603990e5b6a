// The Calibrator facade's streaming API: a camera report computed once and
// shared, or ahead on another thread (camera_branch + add(lidar, camera)),
// gives what add() gives.

#include <l2s/calibrator.hpp>
#include <l2s/sim/simulation.hpp>

#include <gtest/gtest.h>

namespace l2s {
namespace {

TEST(Calibrator, SharedCameraReportGivesTheSameResultAsAdd) {
  auto config = sim::SimulationConfig::paper(8, "vlp16");
  config.frames = 3;
  config.seed = 7;
  const sim::DatasetSimulator simulator(config);

  // The paper preset: no rim refinement, so three frames surely calibrate.
  const auto params = Calibrator::Params::preset("paper");
  Calibrator whole(simulator.cameras(), config.target, params);
  Calibrator shared(simulator.cameras(), config.target, params);
  for (int i = 0; i < config.frames; ++i) {
    const auto frame = simulator.frame(i);
    const FrameReport expected = whole.add(frame.lidar, frame.left, frame.right);
    const BranchReport camera = shared.camera_branch(frame.left, frame.right);
    EXPECT_EQ(shared.result().frames_added, i) << "camera_branch() must not accumulate";
    const FrameReport report = shared.add(frame.lidar, camera);
    EXPECT_EQ(report.id, expected.id);
    EXPECT_EQ(report.lidar.found, expected.lidar.found);
    EXPECT_EQ(report.camera.found, expected.camera.found);
    EXPECT_GE(report.milliseconds, camera.milliseconds);
  }
  const auto a = whole.result();
  const auto b = shared.result();
  ASSERT_TRUE(a.found) << a.reason;
  ASSERT_TRUE(b.found) << b.reason;
  EXPECT_EQ(a.lidar_frames, b.lidar_frames);
  EXPECT_EQ(a.camera_frames, b.camera_frames);
  EXPECT_TRUE(a.T_lidar_camera.isApprox(b.T_lidar_camera, 1e-12));
}

TEST(Calibrator, LidarFromAnotherModelUsesTheSameCameraReport) {
  // The suite's fast path: one simulator per lidar model, images from the
  // first, and one camera report shared by the Calibrators of every model.
  auto config = sim::SimulationConfig::paper(2, "vlp16");
  config.frames = 1;
  config.seed = 3;
  const sim::DatasetSimulator vlp16(config);
  config.lidar = "hdl32";
  config.board_pose = vlp16.board_pose();
  const sim::DatasetSimulator hdl32(config);
  const auto frame = vlp16.frame(0);
  const auto other = hdl32.frame(0);
  ASSERT_TRUE(frame.left.pixels == other.left.pixels) << "images must not depend on the lidar model";
  ASSERT_TRUE(frame.right.pixels == other.right.pixels);

  const auto params = Calibrator::Params::preset("paper");
  Calibrator from_vlp16(vlp16.cameras(), config.target, params);
  const BranchReport camera = from_vlp16.camera_branch(frame.left, frame.right);
  ASSERT_TRUE(camera.found) << camera.reason;
  Calibrator shared(hdl32.cameras(), config.target, params);
  Calibrator whole(hdl32.cameras(), config.target, params);
  const FrameReport report = shared.add(other.lidar, camera);
  const FrameReport expected = whole.add(other.lidar, other.left, other.right);
  ASSERT_TRUE(report.lidar.found) << report.lidar.reason;
  ASSERT_TRUE(expected.camera.found) << expected.camera.reason;
  for (int k = 0; k < 4; ++k) {
    EXPECT_TRUE(report.camera.centers[k].isApprox(expected.camera.centers[k], 1e-12)) << "hole " << k;
    EXPECT_TRUE(report.lidar.centers[k].isApprox(expected.lidar.centers[k], 1e-12)) << "hole " << k;
  }
}

/// `l2s calibrate` runs the camera branches ahead on other threads and adds
/// their reports: with the scene check on (default preset), its verdict and
/// scores, which measure the image edges of the frames it keeps, must be those
/// of add(lidar, left, right), also for raw images (the check's edges are of
/// the rectified image) and for a ring-free lidar (whose window's frames the
/// check takes the camera of).
struct CheckedCase {
  const char* name;
  const char* lidar;
  bool raw;
};

class SharedCameraReportWithCheck : public ::testing::TestWithParam<CheckedCase> {};

TEST_P(SharedCameraReportWithCheck, ChecksAsAddDoes) {
  auto config = sim::SimulationConfig::paper(3, GetParam().lidar);
  config.frames = 4;
  config.seed = 5;
  if (GetParam().raw) config.rig = config.rig.with_real_lenses(sim::DistortionModel::PlumbBob);
  const sim::DatasetSimulator simulator(config);
  auto params = Calibrator::Params::preset("default");
  params.ring_free_frames = 2;
  Calibrator whole(simulator.cameras(), config.target, params);
  Calibrator shared(simulator.cameras(), config.target, params);
  for (int i = 0; i < config.frames; ++i) {
    const auto frame = simulator.frame(i);
    whole.add(frame.lidar, frame.left, frame.right);
    const BranchReport camera = shared.camera_branch(frame.left, frame.right);
    ASSERT_TRUE(camera.observation && camera.check_left) << "the check's part of the camera report";
    EXPECT_TRUE(camera.observation->edges.empty()) << "edges are measured by add(), for kept frames only";
    shared.add(frame.lidar, camera);
  }
  // A frame whose images show no board (the left image twice: no depth in
  // the working range), which the check keeps for its scene evidence.
  const auto frame = simulator.frame(0);
  whole.add(frame.lidar, frame.left, frame.left);
  const BranchReport blind = shared.camera_branch(frame.left, frame.left);
  EXPECT_FALSE(blind.found);
  shared.add(frame.lidar, blind);
  const auto a = whole.result();
  const auto b = shared.result();
  ASSERT_TRUE(a.found) << a.reason;
  ASSERT_TRUE(b.found) << b.reason;
  ASSERT_TRUE(a.checked && b.checked);
  EXPECT_TRUE(a.T_lidar_camera.isApprox(b.T_lidar_camera, 1e-12));
  EXPECT_EQ(a.quality.verdict, b.quality.verdict);
  EXPECT_EQ(a.quality.reasons, b.quality.reasons);
  EXPECT_EQ(a.quality.scores.edge_score, b.quality.scores.edge_score);
  EXPECT_EQ(a.quality.scores.support, b.quality.scores.support);
  ASSERT_EQ(whole.check_frames().size(), shared.check_frames().size());
  for (std::size_t k = 0; k < whole.check_frames().size(); ++k) {
    const CameraObservation& expected = whole.check_frames()[k].camera;
    const CameraObservation& got = shared.check_frames()[k].camera;
    EXPECT_FALSE(got.edges.empty()) << "frame " << k;
    EXPECT_EQ(got.edges.distance, expected.edges.distance) << "frame " << k;
    EXPECT_EQ(got.depth.depth.size(), expected.depth.depth.size()) << "frame " << k;
  }
}

INSTANTIATE_TEST_SUITE_P(Calibrator, SharedCameraReportWithCheck,
                         ::testing::Values(CheckedCase{"rectified", "vlp16", false},
                                           CheckedCase{"raw", "vlp16", true},
                                           CheckedCase{"ring_free", "avia", false}),
                         [](const auto& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace l2s
