// The simulator's geometry against hand-computed ground truth: the setting
// parametrisation of DATASET.md, the board pose, and exact ray casting
// through the board's holes (CSG).

#include <l2s/sim/lidar_model.hpp>
#include <l2s/sim/ray_caster.hpp>
#include <l2s/sim/scene.hpp>
#include <l2s/sim/settings.hpp>
#include <l2s/sim/stereo_rig.hpp>

#include <l2s/error.hpp>

#include <gtest/gtest.h>

#include <cmath>

namespace l2s::sim {
namespace {

constexpr double kDeg = M_PI / 180.0;

TEST(SensorSetting, SettingOneMapsLidarOriginByHand) {
  const SensorSetting s = paper_setting(1);
  const Eigen::Isometry3d T_lidar_camera = s.T_lidar_camera();
  // The lidar origin is at camera body (-0.8, -0.1, 0.4), i.e. optical (0.1, -0.4, -0.8).
  const Eigen::Vector3d p_optical = T_lidar_camera.inverse() * Eigen::Vector3d::Zero();
  EXPECT_NEAR(p_optical.x(), 0.1, 1e-12);
  EXPECT_NEAR(p_optical.y(), -0.4, 1e-12);
  EXPECT_NEAR(p_optical.z(), -0.8, 1e-12);
  // No rotation: camera forward (optical z) is lidar forward (x), optical x is lidar -y.
  EXPECT_TRUE((T_lidar_camera.linear() * Eigen::Vector3d::UnitZ()).isApprox(Eigen::Vector3d::UnitX()));
  EXPECT_TRUE((T_lidar_camera.linear() * Eigen::Vector3d::UnitX()).isApprox(-Eigen::Vector3d::UnitY()));
  EXPECT_TRUE((T_lidar_camera.linear() * Eigen::Vector3d::UnitY()).isApprox(-Eigen::Vector3d::UnitZ()));
}

TEST(SensorSetting, RotationIsZThenYThenXFixedAxes) {
  // Pure yaw 0.5 (setting 2): the lidar's x axis points 0.5 rad to the left in the body frame.
  const Eigen::Isometry3d T = paper_setting(2).T_cambody_lidar();
  EXPECT_TRUE((T.linear() * Eigen::Vector3d::UnitX())
                  .isApprox(Eigen::Vector3d(std::cos(0.5), std::sin(0.5), 0.0), 1e-12));
  // R = Rz Ry Rx for setting 3, built by hand from elementary matrices.
  const double y = 0.3, p = 0.1, r = 0.2;
  Eigen::Matrix3d Rz, Ry, Rx;
  Rz << std::cos(y), -std::sin(y), 0, std::sin(y), std::cos(y), 0, 0, 0, 1;
  Ry << std::cos(p), 0, std::sin(p), 0, 1, 0, -std::sin(p), 0, std::cos(p);
  Rx << 1, 0, 0, 0, std::cos(r), -std::sin(r), 0, std::sin(r), std::cos(r);
  EXPECT_TRUE(paper_setting(3).T_cambody_lidar().linear().isApprox(Rz * Ry * Rx, 1e-12));
}

TEST(SensorSetting, TableHasNineRows) {
  EXPECT_NO_THROW(paper_setting(9));
  EXPECT_THROW(paper_setting(0), ParamError);
  EXPECT_THROW(paper_setting(10), ParamError);
  const SensorSetting s9 = paper_setting(9);
  EXPECT_DOUBLE_EQ(s9.tz, 1.108);
  EXPECT_DOUBLE_EQ(s9.yaw, -0.672);
}

TEST(StereoRig, MatchesTheBumblebeeAndCentredPixels) {
  const StereoRig rig;
  const StereoCamera cams = rig.cameras();
  EXPECT_NEAR(cams.left.fx(), 640.0 / std::tan(0.7505 / 2.0), 1e-9);
  EXPECT_DOUBLE_EQ(cams.left.cx(), 639.5);
  EXPECT_DOUBLE_EQ(cams.left.cy(), 479.5);
  EXPECT_NEAR(cams.baseline(), 0.12, 1e-12);
  // A point on the right camera's optical axis projects to its principal point.
  const Eigen::Vector3d p_left_optical(0.12, 0.0, 5.0);
  const Eigen::Vector2d px = cams.right.project(p_left_optical);
  EXPECT_NEAR(px.x(), 639.5, 1e-9);
  EXPECT_NEAR(px.y(), 479.5, 1e-9);
  EXPECT_TRUE(rig.T_cambody_optical(1).translation().isApprox(Eigen::Vector3d(0, -0.12, 0)));
}

TEST(LidarModel, BeamTablesMatchDataSheets) {
  const LidarModel vlp = LidarModel::vlp16();
  ASSERT_EQ(vlp.rings(), 16);
  EXPECT_NEAR(vlp.elevations.front(), -15 * kDeg, 1e-12);
  EXPECT_NEAR(vlp.elevations.back(), 15 * kDeg, 1e-12);
  EXPECT_EQ(vlp.azimuth_count(), 1800);
  const LidarModel h32 = LidarModel::hdl32();
  ASSERT_EQ(h32.rings(), 32);
  EXPECT_NEAR(h32.elevations.front(), -30.67 * kDeg, 1e-9);
  EXPECT_NEAR(h32.elevations.back(), 10.67 * kDeg, 0.01 * kDeg);
  const LidarModel h64 = LidarModel::hdl64();
  ASSERT_EQ(h64.rings(), 64);
  EXPECT_NEAR(h64.elevations[0], -24.33 * kDeg, 1e-9);
  EXPECT_NEAR(h64.elevations[31], -8.83 * kDeg, 1e-9);
  EXPECT_NEAR(h64.elevations[32], -8.33 * kDeg, 1e-9);
  EXPECT_NEAR(h64.elevations[63], 2.0 * kDeg, 0.01 * kDeg);
  EXPECT_NEAR(h64.elevations[33] - h64.elevations[32], kDeg / 3.0, 1e-12);
  EXPECT_NEAR(h64.elevations[1] - h64.elevations[0], 0.5 * kDeg, 1e-12);
  EXPECT_DOUBLE_EQ(h64.min_range, 0.9);
  EXPECT_THROW(LidarModel::by_name("hdl16"), ParamError);
}

TEST(BoardPose, FacingBoardHasNormalTowardsCamera) {
  const BoardPose pose{3.0, 0.2, -0.1, 0.0, 0.0, 0.0};
  const Eigen::Isometry3d T = pose.T_cambody_board();
  EXPECT_TRUE((T.linear() * Eigen::Vector3d::UnitZ()).isApprox(-Eigen::Vector3d::UnitX()));
  EXPECT_TRUE((T.linear() * Eigen::Vector3d::UnitX()).isApprox(-Eigen::Vector3d::UnitY()));
  EXPECT_TRUE((T.linear() * Eigen::Vector3d::UnitY()).isApprox(Eigen::Vector3d::UnitZ()));
  EXPECT_TRUE(T.translation().isApprox(Eigen::Vector3d(3.0, 0.2, -0.1)));
}

class RayCasterTest : public ::testing::Test {
 protected:
  // A board squarely facing the origin 3 m ahead; wall 3 m behind it.
  Scene scene = make_scene(Target{}, BoardPose{3.0, 0.0, 0.0, 0.0, 0.0, 0.0});
  RayCaster caster{scene};
  Eigen::Vector3d hole_center_body(int hole) const {
    const Eigen::Vector2d c = scene.target.hole_centers()[hole];
    return scene.T_cambody_board * Eigen::Vector3d(c.x(), c.y(), 0.0);
  }
};

TEST_F(RayCasterTest, HitsBoardFrontFaceAtItsDistance) {
  const Hit hit = caster.cast(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX());
  ASSERT_EQ(hit.surface, SurfaceId::Board);
  EXPECT_EQ(hit.part, static_cast<std::uint8_t>(BoardPart::Front));
  EXPECT_NEAR(hit.t, 3.0, 1e-12);
  EXPECT_TRUE(hit.normal.isApprox(-Eigen::Vector3d::UnitX()));
}

TEST_F(RayCasterTest, RayThroughHoleCentreReachesTheWall) {
  for (int hole = 0; hole < 4; ++hole) {
    const Eigen::Vector3d d = hole_center_body(hole).normalized();
    const Hit hit = caster.cast(Eigen::Vector3d::Zero(), d);
    EXPECT_EQ(hit.surface, SurfaceId::Wall) << "hole " << hole;
    EXPECT_NEAR(hit.t * d.x(), 6.0, 1e-9);  // the wall's front face at x = 3 + 3
    EXPECT_EQ(caster.hole_on_front_plane(Eigen::Vector3d::Zero(), d), hole);
  }
}

TEST_F(RayCasterTest, ObliqueRayIntoHoleHitsItsInnerWall) {
  // From far to the side, a ray entering the hole just inside its far rim
  // cannot leave through the 2 cm deep cylinder: it hits the inner wall.
  const Eigen::Vector2d c = scene.target.hole_centers()[0];
  const double r = scene.target.hole_radius;
  // Board frame: entry point near the rim on +x side, ray going -x steeply.
  const Eigen::Vector3d entry_board(c.x() - r + 0.01, c.y(), 0.0);
  const Eigen::Vector3d d_board = Eigen::Vector3d(-1.0, 0.0, -0.5).normalized();
  const Eigen::Vector3d origin = scene.T_cambody_board * (entry_board - 1.0 * d_board);
  const Eigen::Vector3d d = scene.T_cambody_board.linear() * d_board;
  const Hit hit = caster.cast(origin, d);
  ASSERT_EQ(hit.surface, SurfaceId::Board);
  EXPECT_EQ(hit.part, static_cast<std::uint8_t>(BoardPart::HoleWall));
  // It travels 1 m to the front plane, then 0.01 m sideways to the cylinder: +0.01/cos.
  EXPECT_NEAR(hit.t, 1.0 + 0.01 / (2.0 / std::sqrt(5.0)), 1e-9);
  // The same ray well inside the hole (entry at the near side) passes through.
  const Eigen::Vector3d entry2(c.x() + r - 0.01, c.y(), 0.0);
  const Hit through = caster.cast(scene.T_cambody_board * (entry2 - 1.0 * d_board), d);
  EXPECT_NE(through.surface, SurfaceId::Board);
}

TEST_F(RayCasterTest, GroundBelowAndNothingBehind) {
  const Hit down = caster.cast(Eigen::Vector3d::Zero(), -Eigen::Vector3d::UnitZ());
  EXPECT_EQ(down.surface, SurfaceId::Ground);
  EXPECT_NEAR(down.t, 1.5, 1e-12);
  const Hit sky = caster.cast(Eigen::Vector3d::Zero(), Eigen::Vector3d(-1, 0, 0.2).normalized());
  EXPECT_FALSE(sky.hit());
}

}  // namespace
}  // namespace l2s::sim
