#include <l2s/stereo_matcher.hpp>

#include <l2s/error.hpp>

#include "support/board_renderer.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace l2s {
namespace {

/// A textured wall 3 m ahead, fronto-parallel; rendered once for all cases.
const test::StereoPair& wall_pair() {
  static const test::StereoPair pair = [] {
    test::BoardScene scene;
    scene.camera = test::make_stereo_camera();
    scene.with_board = false;
    scene.wall_depth = 3.0;
    scene.noise_sigma = 0.007;
    return test::render_pair(scene);
  }();
  return pair;
}

double median_abs_depth_error(const StereoCloud& cloud, double depth) {
  std::vector<double> errors;
  for (const auto& p : cloud.points) errors.push_back(std::abs(p.z() - depth));
  std::nth_element(errors.begin(), errors.begin() + errors.size() / 2, errors.end());
  return errors[errors.size() / 2];
}

TEST(StereoMatcher, FrontoParallelWallDepthWithinMillimetres) {
  const StereoCamera camera = test::make_stereo_camera();
  const StereoMatcher::Result result = StereoMatcher().match(wall_pair().left, wall_pair().right, camera);
  ASSERT_TRUE(result.found) << result.reason;
  // SGBM leaves min + num disparities columns on the left unmatched.
  EXPECT_GT(result.cloud.size(), 0.7 * 1280 * 960);
  EXPECT_LT(median_abs_depth_error(result.cloud, 3.0), 0.004);
  // Each point projects back onto the pixel it keeps.
  for (std::size_t k = 0; k < result.cloud.size(); k += 997) {
    const Eigen::Vector2d u = camera.left.project(result.cloud.points[k]);
    EXPECT_LT((u - result.cloud.pixels[k].cast<double>()).norm(), 0.51);
  }
  EXPECT_EQ(result.disparity.width, 1280);
  EXPECT_EQ(result.disparity.height, 960);
  const float d = result.disparity.at(640, 480);
  EXPECT_NEAR(d, 1626.0 * 0.12 / 3.0, 0.3);
}

TEST(StereoMatcher, HalfResolutionAndRoiStayAccurate) {
  const StereoCamera camera = test::make_stereo_camera();
  StereoMatcher::Params params;
  params.downscale = 0.5;
  params.roi = {400, 300, 500, 300};
  const StereoMatcher::Result result = StereoMatcher(params).match(wall_pair().left, wall_pair().right, camera);
  ASSERT_TRUE(result.found) << result.reason;
  // SGBM's sub-pixel step locks to ~1/4 px at half resolution: 0.5 px at full
  // resolution, i.e. up to ~2.5 cm at 3 m on a plane of constant disparity.
  EXPECT_LT(median_abs_depth_error(result.cloud, 3.0), 0.03);
  EXPECT_GT(result.cloud.size(), 0.8 * 250 * 150);
  for (const auto& px : result.cloud.pixels) {
    ASSERT_GE(px.x(), 400);
    ASSERT_LT(px.x(), 900);
    ASSERT_GE(px.y(), 300);
    ASSERT_LT(px.y(), 600);
  }
}

TEST(StereoMatcher, RowDownscaleKeepsTheFullResolutionDepth) {
  const StereoCamera camera = test::make_stereo_camera();
  StereoMatcher::Params params;
  params.row_downscale = 0.5;
  const StereoMatcher::Result result = StereoMatcher(params).match(wall_pair().left, wall_pair().right, camera);
  ASSERT_TRUE(result.found) << result.reason;
  EXPECT_EQ(result.disparity.width, 1280);
  EXPECT_EQ(result.disparity.height, 480);
  EXPECT_DOUBLE_EQ(result.disparity.scale, 1.0);
  EXPECT_DOUBLE_EQ(result.disparity.row_scale, 0.5);
  EXPECT_GT(result.cloud.size(), 0.7 * 1280 * 480);
  // Columns keep their resolution, so the disparity (and depth) does too:
  // the same bound as at full resolution, not the half-resolution one.
  EXPECT_LT(median_abs_depth_error(result.cloud, 3.0), 0.004);
  // Each point projects back onto its pixel; a cell spans two rows.
  for (std::size_t k = 0; k < result.cloud.size(); k += 997) {
    const Eigen::Vector2d u = camera.left.project(result.cloud.points[k]);
    EXPECT_LT(std::abs(u.x() - result.cloud.pixels[k].x()), 0.51);
    EXPECT_LT(std::abs(u.y() - result.cloud.pixels[k].y()), 0.51);
  }
}

TEST(StereoMatcher, SurfaceBeyondTheWorkingRangeMakesNoPlaneAtItsEdge) {
  // Another rig (fx 985 px): a window fixed in pixels would cover other
  // depths on it. The wall stands beyond the working range; SGBM clamps what
  // it cannot match to its search's edge, which must not become a plane of
  // points at max_depth.
  test::BoardScene scene;
  scene.camera = test::make_stereo_camera(1280, 960, 985.0, 0.12);
  scene.with_board = false;
  scene.wall_depth = 5.0;
  scene.noise_sigma = 0.007;
  const test::StereoPair pair = test::render_pair(scene);
  StereoMatcher::Params params;
  params.min_depth = 1.0;
  params.max_depth = 4.0;
  const StereoMatcher::Result result = StereoMatcher(params).match(pair.left, pair.right, scene.camera);
  EXPECT_NEAR(result.min_disparity, 985.0 * 0.12 / 4.0, 1e-9);  // the window follows the rig
  EXPECT_NEAR(result.max_disparity, 985.0 * 0.12 / 1.0, 1e-9);
  std::size_t at_edge = 0;
  for (const auto& p : result.cloud.points) at_edge += p.z() > 0.97 * params.max_depth ? 1 : 0;
  EXPECT_LT(at_edge, 1280u * 960u / 100u) << result.cloud.size() << " points, " << result.window_edge << " dropped";
  EXPECT_GT(result.window_edge, 1280u * 960u / 2u);
}

TEST(StereoMatcher, RejectsInvalidParamsAndMismatchedImages) {
  StereoMatcher::Params params;
  params.block_size = 4;
  try {
    StereoMatcher{params};
    FAIL() << "expected ParamError";
  } catch (const ParamError& error) {
    EXPECT_EQ(error.field(), "block_size");
  }
  const Image small(64, 48);
  EXPECT_THROW(StereoMatcher().match(wall_pair().left, small, test::make_stereo_camera()), InputError);
}

}  // namespace
}  // namespace l2s
