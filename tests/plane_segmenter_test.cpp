#include <l2s/error.hpp>
#include <l2s/pass_through_filter.hpp>
#include <l2s/plane_segmenter.hpp>

#include "support/ring_scene.hpp"

#include <gtest/gtest.h>

namespace l2s {
namespace {

using test::board_pose;
using test::kDeg;
using test::Scene;

/// Angle between the planes' normals [rad] and offset difference [m], sign-free.
::testing::AssertionResult plane_near(const Plane& found, const Plane& truth, double angle, double offset) {
  const Plane a = found.offset() < 0 ? Plane(-found.normal(), -found.offset()) : found;
  const Plane b = truth.offset() < 0 ? Plane(-truth.normal(), -truth.offset()) : truth;
  const double e_angle = std::acos(std::min(1.0, a.normal().dot(b.normal())));
  const double e_offset = std::abs(a.offset() - b.offset());
  if (e_angle <= angle && e_offset <= offset) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "normal off by " << e_angle / kDeg << " deg, offset by " << e_offset
                                       << " m; found n = " << a.normal().transpose() << " d = " << a.offset();
}

/// The share of `inliers` that lie on the board (near its face, inside its outline).
double board_share(const std::vector<Eigen::Vector3d>& points, const std::vector<std::size_t>& inliers,
                   const Scene& scene) {
  std::size_t on_board = 0;
  for (std::size_t i : inliers) {
    const Eigen::Vector3d p = scene.T_sensor_board.inverse() * points[i];
    if (std::abs(p.x()) < scene.target.board_width / 2 + 0.03 && std::abs(p.y()) < scene.target.board_height / 2 + 0.03)
      ++on_board;
  }
  return inliers.empty() ? 0.0 : static_cast<double>(on_board) / inliers.size();
}

std::vector<Eigen::Vector3d> front_box(const LidarCloud& cloud) {
  PassThroughFilter::Params box;
  box.min_xyz = Eigen::Vector3d(0.5, -4.0, -2.0);
  box.max_xyz = Eigen::Vector3d(8.0, 4.0, 2.0);
  return select(cloud, PassThroughFilter(box).filter(cloud.points).kept).points;
}

TEST(PlaneSegmenter, FindsTiltedBoardAmongWallAndGround) {
  Scene scene;
  scene.T_sensor_board = board_pose({3.0, 0.4, 0.03}, 20.0 * kDeg, 10.0 * kDeg);
  const auto points = front_box(test::scan(scene, test::vlp16(), 1));
  const auto result = PlaneSegmenter().segment(points, scene.target);
  ASSERT_TRUE(result.found) << result.reason;
  EXPECT_TRUE(plane_near(result.plane, scene.visible_plane(), 1.0 * kDeg, 0.01));
  EXPECT_GT(result.plane.offset(), 0.0);  // normal towards the sensor
  EXPECT_GT(board_share(points, result.inliers, scene), 0.98);
  // The wall is bigger and vertical too: it must have been seen and rejected.
  ASSERT_GE(result.candidates.size(), 2u);
  EXPECT_FALSE(result.candidates.front().plausible);
  EXPECT_NE(result.candidates.front().reason.find("larger than the board"), std::string::npos)
      << result.candidates.front().reason;
  ASSERT_FALSE(result.ranking.empty());
  EXPECT_EQ(result.inliers, result.candidates[result.ranking.front()].inliers);
  EXPECT_LT(result.rms, 0.012);
}

TEST(PlaneSegmenter, FindsBoardInAWholeSweep) {
  const Scene scene;  // no pass-through: ground rings all around, the wall in front
  const LidarCloud sweep = test::scan(scene, test::vlp16(), 2);
  const auto result = PlaneSegmenter().segment(sweep.points, scene.target);
  ASSERT_TRUE(result.found) << result.reason;
  EXPECT_TRUE(plane_near(result.plane, scene.visible_plane(), 1.0 * kDeg, 0.01));
  EXPECT_GT(board_share(sweep.points, result.inliers, scene), 0.98);
}

TEST(PlaneSegmenter, FindsBoardIn64BeamSweep) {
  Scene scene;
  scene.T_sensor_board = board_pose({4.0, -0.5, 0.2}, -15.0 * kDeg);
  const auto points = front_box(test::scan(scene, test::beams64(), 3));
  const auto result = PlaneSegmenter().segment(points, scene.target);
  ASSERT_TRUE(result.found) << result.reason;
  EXPECT_TRUE(plane_near(result.plane, scene.visible_plane(), 1.0 * kDeg, 0.01));
}

TEST(PlaneSegmenter, FindsPaper2017BoardBehindTheSensor) {
  Scene scene;
  scene.target = Target::paper2017();
  scene.T_sensor_board = board_pose({-3.0, 0.5, 0.0});
  scene.planes.push_back(Plane(Eigen::Vector3d::UnitX(), 6.0));  // a wall at x = -6 as well
  const LidarCloud sweep = test::scan(scene, test::vlp16(), 4);
  const auto result = PlaneSegmenter().segment(sweep.points, scene.target);
  ASSERT_TRUE(result.found) << result.reason;
  EXPECT_TRUE(plane_near(result.plane, scene.visible_plane(), 1.0 * kDeg, 0.01));
}

TEST(PlaneSegmenter, SameSeedSameResult) {
  const Scene scene;
  const auto points = front_box(test::scan(scene, test::vlp16(), 5));
  const PlaneSegmenter segmenter;
  const auto a = segmenter.segment(points, scene.target);
  const auto b = segmenter.segment(points, scene.target);
  ASSERT_TRUE(a.found);
  EXPECT_EQ(a.inliers, b.inliers);
  EXPECT_EQ(a.plane.coeffs(), b.plane.coeffs());
}

TEST(PlaneSegmenter, ExplainsWhyThereIsNoBoard) {
  Scene scene;
  scene.has_board = false;
  const auto result = PlaneSegmenter().segment(front_box(test::scan(scene, test::vlp16(), 6)), scene.target);
  EXPECT_FALSE(result.found);
  EXPECT_FALSE(result.reason.empty());
  ASSERT_FALSE(result.candidates.empty());
  for (const PlaneCandidate& c : result.candidates) {
    EXPECT_FALSE(c.plausible);
    EXPECT_FALSE(c.reason.empty());
  }
}

TEST(PlaneSegmenter, FindsBoardInDenseStereoLikeCloud) {
  // A 640 x 400 grid of rays over a 60 x 40 degree view, depth noise 2 cm,
  // returned in the camera optical frame (x right, y down, z forward).
  Scene scene;
  scene.T_sensor_board = board_pose({3.5, 0.3, 0.0}, 25.0 * kDeg);
  std::mt19937_64 rng(7);
  std::normal_distribution<double> noise(0.0, 0.02);
  std::vector<Eigen::Vector3d> points;
  for (int row = 0; row < 400; ++row)
    for (int col = 0; col < 640; ++col) {
      const Eigen::Vector3d d = test::ray((20.0 - 0.1 * row) * kDeg, (30.0 - 0.09375 * col) * kDeg);
      const double r = scene.cast(d);
      if (r == test::kNoHit) continue;
      const Eigen::Vector3d p = d * (r + noise(rng));
      points.emplace_back(-p.y(), -p.z(), p.x());
    }
  const auto result = PlaneSegmenter(PlaneSegmenter::Params::stereo()).segment(points, scene.target);
  ASSERT_TRUE(result.found) << result.reason;
  const Plane truth = scene.visible_plane();
  const Eigen::Vector3d n(-truth.normal().y(), -truth.normal().z(), truth.normal().x());
  EXPECT_TRUE(plane_near(result.plane, Plane(n, truth.offset()), 1.0 * kDeg, 0.01));
}

TEST(PlaneSegmenter, RejectsInvalidParamsNamingTheField) {
  PlaneSegmenter::Params params;
  params.max_angle = 2.0;
  try {
    PlaneSegmenter segmenter(params);
    FAIL() << "expected ParamError";
  } catch (const ParamError& e) {
    EXPECT_EQ(e.field(), "max_angle");
  }
}

}  // namespace
}  // namespace l2s
