// The scene check on randomised scenes (issue 11: ok for good results on any
// scene, not only the paper's). Each scene here is one whose good calibration
// the check once called suspect or failed, for a reason of its own:
// - a ring-free lidar: its detection comes with the last sweep of a window,
//   whose images may not show the board, and one sweep holds too few depth
//   edges to check (the check had no evidence and failed every such result);
// - a board 12 cm before a brick wall: stereo matches fattened over its edges
//   tilt the stereo plane by degrees (the lidar board looked tilted);
// - a flat edge score: its optimum lies anywhere within the flat top, so the
//   "best alignment 18 px away" was noise (the transform scored as well);
// - a wood-grain board with the grain along the rows: SGBM cannot match it
//   along them and fills the face in from its surroundings, 1.2 px of
//   disparity (18 mm) behind the board its rims place right; the lidar
//   board was measured against that stereo plane.
// `l2s simulate --random-scene SEED` writes each as a dataset.

#include <l2s/calibrator.hpp>
#include <l2s/metrics.hpp>
#include <l2s/sim/random_scene.hpp>

#include <gtest/gtest.h>

#include <cmath>

namespace l2s {
namespace {

struct SceneCase {
  const char* name;
  std::uint64_t seed;
  int frames;
};

class CheckOnRandomScenes : public ::testing::TestWithParam<SceneCase> {};

TEST_P(CheckOnRandomScenes, AGoodCalibrationIsOk) {
  const SceneCase& c = GetParam();
  const sim::RandomScene scene = sim::make_random_scene(c.seed, c.frames, 1.0, 0, sim::BoardDraw::Classic);
  const sim::DatasetSimulator& simulator = *scene.simulator;
  auto params = Calibrator::Params::preset("default");
  params.ring_free_frames = c.frames;  // one window of the whole recording
  Calibrator calibrator(simulator.cameras(), simulator.config().target, params);
  for (int i = 0; i < c.frames; ++i) {
    const auto frame = simulator.frame(i);
    calibrator.add(frame.lidar, frame.left, frame.right);
  }
  const Calibrator::Result result = calibrator.result();
  ASSERT_TRUE(result.found) << scene.summary << "\n" << result.reason;
  const PoseError error = pose_error(result.T_lidar_camera, simulator.config().T_lidar_camera());
  // Only a good result must be ok; the scene was chosen for one.
  ASSERT_LT(error.translation, 0.02) << scene.summary;
  ASSERT_LT(error.rotation, 0.5 * M_PI / 180) << scene.summary;
  ASSERT_TRUE(result.checked);
  EXPECT_EQ(result.quality.verdict, CalibrationCheck::Verdict::Ok) << scene.summary << "\n" << describe(result.quality);
  EXPECT_GE(result.quality.scores.edge_points, calibrator.params().check.min_edge_points) << describe(result.quality);
  EXPECT_LT(result.quality.scores.plane_tilt, 0.5 * M_PI / 180) << describe(result.quality);
}

INSTANTIATE_TEST_SUITE_P(Scenes, CheckOnRandomScenes,
                         ::testing::Values(SceneCase{"AviaWindowWithoutTheBoardInItsLastImages", 1233026446, 12},
                                           SceneCase{"BoardBeforeANearBrickWall", 89189780, 4},
                                           SceneCase{"FlatEdgeScore", 1250646734, 4},
                                           SceneCase{"WoodGrainAlongTheRows", 2108111155, 4}),
                         [](const auto& info) { return std::string(info.param.name); });

// A ring-free lidar finds the board once per accumulated window: 30 frames
// gave the check one frame with the board on both sides. On that one frame's
// evidence the scene preferred the fit with the camera's labels turned by
// 180 deg, and the calibrator adopted it (1807015301: 1.7 m / 180 deg off,
// and `ok`). Frames without the board fill the check up (their depth edges
// and stereo depth still test a transform), and a hypothesis no longer wins
// by bringing more edges into a textured image (2095762356: with the frames
// but without that, the right labels were turned). The labels as the sensors
// gave them stand, and the result is right and ok.
class LabelsOnRandomScenes : public ::testing::TestWithParam<SceneCase> {};

TEST_P(LabelsOnRandomScenes, TheRightLabelsStandOnTheWholeRecordingsEvidence) {
  const SceneCase& c = GetParam();
  const sim::RandomScene scene = sim::make_random_scene(c.seed, c.frames, 1.0, 0, sim::BoardDraw::Classic);
  const sim::DatasetSimulator& simulator = *scene.simulator;
  Calibrator calibrator(simulator.cameras(), simulator.config().target);
  for (int i = 0; i < c.frames; ++i) {
    const auto frame = simulator.frame(i);
    calibrator.add(frame.lidar, frame.left, frame.right);
  }
  const Calibrator::Result result = calibrator.result();
  ASSERT_TRUE(result.found) << scene.summary << "\n" << result.reason;
  EXPECT_LE(result.lidar_frames, 2) << "the case needs a lidar that finds the board in few frames";
  EXPECT_GE(result.quality.edge_frames, calibrator.params().check_frames) << describe(result.quality);
  EXPECT_EQ(result.labels_turned, 0) << describe(result.quality);
  const PoseError error = pose_error(result.T_lidar_camera, simulator.config().T_lidar_camera());
  EXPECT_LT(error.translation, 0.02) << scene.summary;
  EXPECT_LT(error.rotation, 0.5 * M_PI / 180) << scene.summary;
  EXPECT_EQ(result.quality.verdict, CalibrationCheck::Verdict::Ok) << scene.summary << "\n" << describe(result.quality);
}

INSTANTIATE_TEST_SUITE_P(Scenes, LabelsOnRandomScenes,
                         ::testing::Values(SceneCase{"Mid360BeforeOpenSpace", 1807015301, 30},
                                           SceneCase{"Mid360BeforeTexturedGround", 2095762356, 30}),
                         [](const auto& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace l2s
