// Simulated lidar sweeps against the sensor tables and the scene geometry.

#include <l2s/sim/lidar_simulator.hpp>
#include <l2s/sim/placement.hpp>
#include <l2s/sim/ray_caster.hpp>
#include <l2s/sim/settings.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <map>

namespace l2s::sim {
namespace {

struct LidarCase {
  std::string model;
  int setting;
};

std::string case_name(const ::testing::TestParamInfo<LidarCase>& info) {
  return info.param.model + "_setting" + std::to_string(info.param.setting);
}

class LidarSweepTest : public ::testing::TestWithParam<LidarCase> {
 protected:
  void SetUp() override {
    model = LidarModel::by_name(GetParam().model);
    setting = paper_setting(GetParam().setting);
    const PlacementResult placed =
        find_placement(Target{}, setting, {LidarModel::vlp16(), LidarModel::hdl32(), LidarModel::hdl64()});
    ASSERT_TRUE(placed.found);
    scene = make_scene(Target{}, placed.pose);
  }
  LidarModel model;
  SensorSetting setting;
  Scene scene;
};

TEST_P(LidarSweepTest, ElevationsAndRingsMatchTheBeamTable) {
  const RayCaster caster(scene);
  LidarSimulator::Params params;
  params.noise_factor = 3.0;  // noise is along the ray, so elevations stay exact
  const LidarSimulator lidar(model, params);
  const LidarCloud cloud = lidar.sweep(caster, setting.T_cambody_lidar(), 4);
  ASSERT_GT(cloud.size(), 1000u);
  ASSERT_EQ(cloud.ring.size(), cloud.size());
  ASSERT_EQ(cloud.intensity.size(), cloud.size());
  std::map<int, int> per_ring;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const Eigen::Vector3d& p = cloud.points[i];
    const double elevation = std::atan2(p.z(), std::hypot(p.x(), p.y()));
    ASSERT_NEAR(elevation, model.elevations[cloud.ring[i]], 1e-9) << "point " << i;
    const double range = p.norm();
    ASSERT_GE(range, model.min_range - 0.1);
    ASSERT_LE(range, model.max_range + 0.1);
    ++per_ring[cloud.ring[i]];
  }
  // Every ring sees at least the wall or the ground somewhere in the sweep.
  EXPECT_EQ(static_cast<int>(per_ring.size()), model.rings());
  // Azimuths sit on the grid offset + k * step, with the offset within one step.
  const double offset = lidar.azimuth_offset(4);
  EXPECT_GE(offset, 0.0);
  EXPECT_LT(offset, model.azimuth_step);
  for (std::size_t i = 0; i < cloud.size(); i += 97) {
    double az = std::atan2(cloud.points[i].y(), cloud.points[i].x());
    if (az < offset) az += 2.0 * M_PI;
    const double k = (az - offset) / model.azimuth_step;
    EXPECT_NEAR(k, std::round(k), 1e-6);
  }
}

TEST_P(LidarSweepTest, RaysThroughHolesLandBehindTheBoard) {
  const RayCaster caster(scene);
  LidarSimulator::Params params;
  params.noise_factor = 1.0;
  const LidarSimulator lidar(model, params);
  const Eigen::Isometry3d T_cambody_lidar = setting.T_cambody_lidar();
  std::vector<SurfaceId> surfaces;
  const LidarCloud cloud = lidar.sweep(caster, T_cambody_lidar, 0, &surfaces);
  ASSERT_EQ(surfaces.size(), cloud.size());

  // Ground truth: the board plane and hole discs, from the scene, in the lidar frame.
  const Eigen::Isometry3d T_lidar_board = T_cambody_lidar.inverse() * scene.T_cambody_board;
  const Eigen::Isometry3d T_board_lidar = T_lidar_board.inverse();
  const auto holes = scene.target.hole_centers();
  std::array<int, 4> through{};
  int on_board = 0;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const Eigen::Vector3d dir = cloud.points[i].normalized();
    const Eigen::Vector3d o = T_board_lidar.translation();
    const Eigen::Vector3d d = T_board_lidar.linear() * dir;
    if (std::abs(d.z()) < 1e-9) continue;
    const double t_plane = -o.z() / d.z();  // range to the board's front plane
    const double t_back = (-scene.target.board_thickness - o.z()) / d.z();
    if (t_plane <= 0) continue;
    const Eigen::Vector2d q = (o + t_plane * d).head<2>();
    const Eigen::Vector2d q_back = (o + t_back * d).head<2>();
    // A hole is a cylinder: a ray passes it iff it crosses both the front and
    // the back face inside the disc (the segment between is then inside too).
    const double r = scene.target.hole_radius;
    int hole = -1;
    bool near_hole = false;
    for (int h = 0; h < 4; ++h) {
      if ((q - holes[h]).norm() < r - 0.002 && (q_back - holes[h]).norm() < r - 0.002) hole = h;
      if ((q - holes[h]).norm() < r + 0.002) near_hole = true;
    }
    const bool on_face = std::abs(q.x()) < scene.target.board_width / 2 - 0.002 &&
                         std::abs(q.y()) < scene.target.board_height / 2 - 0.002;
    if (hole >= 0) {
      // Through the hole: a return far behind the board plane, never on the board.
      EXPECT_NE(surfaces[i], SurfaceId::Board);
      EXPECT_GT(cloud.points[i].norm(), t_plane + 1.0);
      ++through[hole];
    } else if (on_face && !near_hole) {
      // Everywhere else on the face the board is hit, at the plane's range.
      ASSERT_EQ(surfaces[i], SurfaceId::Board);
      EXPECT_NEAR(cloud.points[i].norm(), t_plane, 0.06);  // 7 sigma of 0.008 m
      ++on_board;
    }
  }
  EXPECT_GT(on_board, 50);
  for (int h = 0; h < 4; ++h) EXPECT_GE(through[h], 4) << "hole " << h;
}

INSTANTIATE_TEST_SUITE_P(Models, LidarSweepTest,
                         ::testing::Values(LidarCase{"vlp16", 1}, LidarCase{"hdl32", 4},
                                           LidarCase{"hdl64", 8}, LidarCase{"vlp16", 9}),
                         case_name);

TEST(LidarSimulator, SameSeedSameSweepAnyThreadCount) {
  const Scene scene = make_scene(Target{}, BoardPose{3.0, 0.0, -0.1, 0.2, 0.05, 0.05});
  const RayCaster caster(scene);
  LidarSimulator::Params one, two;
  one.threads = 1;
  two.threads = 3;
  const Eigen::Isometry3d T = paper_setting(3).T_cambody_lidar();
  const LidarCloud a = LidarSimulator(LidarModel::vlp16(), one).sweep(caster, T, 2);
  const LidarCloud b = LidarSimulator(LidarModel::vlp16(), two).sweep(caster, T, 2);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) ASSERT_EQ(a.points[i], b.points[i]);
  // A different frame draws a different offset and noise.
  const LidarCloud c = LidarSimulator(LidarModel::vlp16(), one).sweep(caster, T, 3);
  EXPECT_NE(a.points.front(), c.points.front());
}

TEST(LidarSimulator, RangeNoiseHasThePapersSigma) {
  const Scene scene = make_scene(Target{}, BoardPose{3.0, 0.0, 0.0, 0.0, 0.0, 0.0});
  const RayCaster caster(scene);
  LidarSimulator::Params noisy, exact;
  noisy.noise_factor = 2.0;
  exact.noise_factor = 0.0;
  const Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  const LidarCloud a = LidarSimulator(LidarModel::hdl64(), noisy).sweep(caster, T, 0);
  const LidarCloud b = LidarSimulator(LidarModel::hdl64(), exact).sweep(caster, T, 0);
  ASSERT_EQ(a.size(), b.size());  // same offset stream, same rays
  double sum = 0, sum2 = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double e = a.points[i].norm() - b.points[i].norm();
    sum += e;
    sum2 += e * e;
  }
  const double n = static_cast<double>(a.size());
  EXPECT_NEAR(sum / n, 0.0, 0.001);
  EXPECT_NEAR(std::sqrt(sum2 / n), 2.0 * 0.008, 0.0008);
}

TEST(LidarSimulator, BoardIsBrighterThanWall) {
  EXPECT_GT(LidarSimulator::intensity(SurfaceId::Board, 0.8),
            LidarSimulator::intensity(SurfaceId::Wall, 1.0));
}

}  // namespace
}  // namespace l2s::sim
