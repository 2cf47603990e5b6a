#include <l2s/board_pose_refiner.hpp>

#include <l2s/error.hpp>

#include "support/board_renderer.hpp"
#include "support/test_data.hpp"

#include <gtest/gtest.h>

namespace l2s {
namespace {

/// A pose error of ~1.5 deg tilt and 5 mm offset, as a stereo plane fit leaves.
Eigen::Isometry3d perturbed(const Eigen::Isometry3d& T_true) {
  Eigen::Isometry3d T = T_true;
  const Eigen::Vector3d axis = Eigen::Vector3d(0.7, 0.6, 0.2).normalized();
  T.linear() = Eigen::AngleAxisd(1.5 * M_PI / 180.0, axis).toRotationMatrix() * T.linear();
  T.translation() += Eigen::Vector3d(0.003, -0.002, 0.0035);  // |offset| = 5 mm
  return T;
}

struct Case {
  const char* name;
  double distance, yaw, pitch, x;
  bool lit = false;  ///< shade the holes' inner wall with the simulator's light
};

class BoardPoseRefinerRendered : public ::testing::TestWithParam<Case> {};

TEST_P(BoardPoseRefinerRendered, RecoversTruePoseFromPerturbedStart) {
  const Case c = GetParam();
  test::BoardScene scene;
  scene.camera = test::make_stereo_camera();
  scene.T_camera_board = test::board_pose(c.distance, c.yaw, c.pitch, c.x);
  scene.noise_sigma = 0.007;
  if (c.lit) scene.hole_wall_light = test::simulator_light();
  const test::StereoPair pair = test::render_pair(scene);

  const BoardPoseRefiner::Result result = BoardPoseRefiner().refine(
      pair.left, pair.right, scene.camera, scene.target, perturbed(scene.T_camera_board));
  ASSERT_TRUE(result.converged) << result.reason;
  EXPECT_POSE_NEAR(result.T_camera_board, scene.T_camera_board, 0.1, 0.001);
  EXPECT_GT(result.samples, 500);
  EXPECT_GT(result.edge_fraction, 0.8);
  EXPECT_LT(result.rms_px, 0.5);
  const auto holes = scene.target.hole_centers();
  for (int h = 0; h < 4; ++h) {
    const Eigen::Vector3d truth = scene.T_camera_board * Eigen::Vector3d(holes[h].x(), holes[h].y(), 0.0);
    EXPECT_LT((result.centers[h] - truth).norm(), 0.0015) << "hole " << h;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Poses, BoardPoseRefinerRendered,
    ::testing::Values(Case{"FacingAt3m", 3.0, 0.0, 0.0, 0.0}, Case{"Yaw25At3m", 3.0, 25.0 * M_PI / 180.0, 0.0, 0.2},
                      Case{"YawPitchAt4m", 4.0, -15.0 * M_PI / 180.0, 8.0 * M_PI / 180.0, -0.3},
                      // Turned so that each hole shows the inner wall on its shadowed side:
                      // as dark as the background, so the face-to-wall edge beside the
                      // back rim is the strongest one in reach (paper setting 8).
                      Case{"ShadowedHoleWallAt2m6", 2.6, -0.2, 0.0, 0.0, true}),
    [](const ::testing::TestParamInfo<Case>& info) { return std::string(info.param.name); });

TEST(BoardPoseRefiner, ImagesWithoutBoardGiveReason) {
  test::BoardScene scene;
  scene.camera = test::make_stereo_camera(320, 240, 400.0);
  scene.with_board = false;
  const test::StereoPair pair = test::render_pair(scene);
  const BoardPoseRefiner::Result result =
      BoardPoseRefiner().refine(pair.left, pair.right, scene.camera, scene.target, test::board_pose(3.0));
  EXPECT_FALSE(result.converged);
  EXPECT_FALSE(result.reason.empty());
  // Wall texture alone yields edge samples, and the pose may well settle on
  // them (rms ~0.8 px, steps ~0.01 px); what tells it from a board is that
  // few of the rim samples found an edge.
  EXPECT_LT(result.edge_fraction, BoardPoseRefiner::Params{}.min_edge_fraction);
}

TEST(BoardPoseRefiner, RejectsInvalidParams) {
  BoardPoseRefiner::Params params;
  params.final_search_range_px = 10.0;
  try {
    BoardPoseRefiner{params};
    FAIL() << "expected ParamError";
  } catch (const ParamError& error) {
    EXPECT_EQ(error.field(), "final_search_range_px");
  }
}

}  // namespace
}  // namespace l2s
