// Ring-free lidars: the non-repetitive rosette scan of Livox Avia- and
// Mid-360-like sensors. No rings, the data sheets' point rates and fields of
// view, and coverage of a static board that grows with accumulation time.

#include <l2s/sim/lidar_simulator.hpp>
#include <l2s/sim/ray_caster.hpp>

#include <l2s/error.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <ostream>
#include <set>

namespace l2s::sim {
namespace {

constexpr double kDeg = M_PI / 180.0;

TEST(RosetteModel, ByNameAndDataSheetFigures) {
  const LidarModel avia = LidarModel::by_name("avia");
  EXPECT_FALSE(avia.has_rings());
  EXPECT_EQ(avia.rings(), 0);
  EXPECT_EQ(avia.rosette.shots_per_frame(), 24000);  // 240k points/s, 10 Hz frames
  const LidarModel mid = LidarModel::by_name("mid360");
  EXPECT_EQ(mid.rosette.shots_per_frame(), 20000);   // 200k points/s
  EXPECT_NEAR(mid.min_range, 0.1, 1e-12);
  EXPECT_NEAR(avia.range_sigma0, 0.02, 1e-12);
  EXPECT_TRUE(LidarModel::vlp16().has_rings());
  LidarModel bad = avia;
  bad.rosette.prism_rate_b = bad.rosette.prism_rate_a;
  EXPECT_THROW(bad.validate(), ParamError);
}

struct Extent {
  double az_min = 1e9, az_max = -1e9, el_min = 1e9, el_max = -1e9;
};

Extent extent_of(const std::vector<Eigen::Vector3d>& directions) {
  Extent e;
  for (const Eigen::Vector3d& d : directions) {
    const double az = std::atan2(d.y(), d.x()), el = std::asin(d.z());
    e.az_min = std::min(e.az_min, az), e.az_max = std::max(e.az_max, az);
    e.el_min = std::min(e.el_min, el), e.el_max = std::max(e.el_max, el);
  }
  return e;
}

TEST(RosetteScan, AviaFieldOfViewIs70By77Degrees) {
  const LidarSimulator lidar(LidarModel::avia());
  EXPECT_EQ(lidar.firings_per_sweep(), 24000);
  const std::vector<Eigen::Vector3d> directions = lidar.firing_directions(0);
  ASSERT_EQ(directions.size(), 24000u);
  const Extent e = extent_of(directions);
  // Inside the data sheet's 70.4 x 77.2 deg, and reaching its edges in one frame.
  EXPECT_GE(e.az_min, -35.2 * kDeg - 1e-9);
  EXPECT_LE(e.az_max, 35.2 * kDeg + 1e-9);
  EXPECT_GE(e.el_min, -38.6 * kDeg - 1e-9);
  EXPECT_LE(e.el_max, 38.6 * kDeg + 1e-9);
  EXPECT_LT(e.az_max - e.az_min, 70.4 * kDeg + 1e-9);
  EXPECT_GT(e.az_max - e.az_min, 68.0 * kDeg);
  EXPECT_GT(e.el_max - e.el_min, 75.0 * kDeg);
}

TEST(RosetteScan, Mid360SeesAllAroundFromMinus7To52Degrees) {
  const LidarSimulator lidar(LidarModel::mid360());
  const std::vector<Eigen::Vector3d> directions = lidar.firing_directions(3);
  ASSERT_EQ(directions.size(), 20000u);
  const Extent e = extent_of(directions);
  EXPECT_GE(e.el_min, -7.0 * kDeg - 1e-9);
  EXPECT_LE(e.el_max, 52.0 * kDeg + 1e-9);
  EXPECT_GT(e.el_max - e.el_min, 57.0 * kDeg);
  // One frame already looks all around: every 10 deg azimuth sector is hit.
  std::set<int> sectors;
  for (const Eigen::Vector3d& d : directions)
    sectors.insert(static_cast<int>(std::floor((std::atan2(d.y(), d.x()) + M_PI) / (10.0 * kDeg))) % 36);
  EXPECT_EQ(sectors.size(), 36u);
}

TEST(RosetteScan, FramesContinueThePatternWithoutRepeating) {
  const LidarSimulator lidar(LidarModel::avia());
  // Share of 0.25 deg cells of the central 20 x 20 deg hit after 1 and 10 frames.
  std::set<std::pair<int, int>> cells;
  const auto add = [&](std::uint64_t frame) {
    for (const Eigen::Vector3d& d : lidar.firing_directions(frame)) {
      const double az = std::atan2(d.y(), d.x()) / kDeg, el = std::asin(d.z()) / kDeg;
      if (std::abs(az) < 10.0 && std::abs(el) < 10.0)
        cells.insert({static_cast<int>(std::floor(az * 4)), static_cast<int>(std::floor(el * 4))});
    }
  };
  add(0);
  const double one = cells.size() / 6400.0;
  for (std::uint64_t f = 1; f < 10; ++f) add(f);
  const double ten = cells.size() / 6400.0;
  EXPECT_LT(one, 0.6);
  EXPECT_GT(ten, one + 0.25);
  EXPECT_GT(ten, 0.9);
  // Frame 1 continues frame 0 rather than repeating it.
  EXPECT_GT((lidar.firing_directions(1)[0] - lidar.firing_directions(0)[0]).norm(), 1e-3);
}

TEST(RosetteLidar, CloudHasNoRingAndKeepsThePointRateWithNaNs) {
  const Scene scene = make_scene(Target{}, BoardPose{3.0, 0.0, 0.0, 0.2, 0.0, 0.0});
  const RayCaster caster(scene);
  LidarSimulator::Params params;
  params.nan_for_no_return = true;
  const LidarSimulator lidar(LidarModel::avia(), params);
  const LidarCloud cloud = lidar.sweep(caster, Eigen::Isometry3d::Identity(), 2);
  EXPECT_TRUE(cloud.ring.empty());
  ASSERT_EQ(cloud.size(), 24000u);
  ASSERT_EQ(cloud.intensity.size(), cloud.size());
  int valid = 0;
  for (const Eigen::Vector3d& p : cloud.points) valid += p.allFinite();
  EXPECT_GT(valid, 15000);  // the sky above the wall gives no returns
  EXPECT_LT(valid, 24000);
  // Without NaNs only the returns remain, in the same order.
  const LidarCloud sparse = LidarSimulator(LidarModel::avia()).sweep(caster, Eigen::Isometry3d::Identity(), 2);
  EXPECT_EQ(static_cast<int>(sparse.size()), valid);
}

struct CoverageCase {
  std::string model;
  double distance;      ///< [m]
  double min_coverage;  ///< of 3 cm cells of the board face after 2 s
};

void PrintTo(const CoverageCase& c, std::ostream* os) { *os << c.model << " at " << c.distance << " m"; }

class RosetteCoverage : public ::testing::TestWithParam<CoverageCase> {};

TEST_P(RosetteCoverage, CoversTheBoardDenselyAfterTwoSeconds) {
  const CoverageCase& c = GetParam();
  // The Mid-360 looks from -7 deg up: its board stands 10 deg above the horizon.
  const double z = c.model == "mid360" ? c.distance * std::tan(10.0 * kDeg) : 0.0;
  const Scene scene = make_scene(Target{}, BoardPose{c.distance, 0.0, z, 0.2, 0.0, 0.0});
  const RayCaster caster(scene);
  const LidarSimulator lidar(LidarModel::by_name(c.model));
  const Target& t = scene.target;
  const Eigen::Isometry3d T_board = scene.T_cambody_board.inverse();
  const double cell = 0.03;
  const int nx = static_cast<int>(t.board_width / cell), ny = static_cast<int>(t.board_height / cell);
  // Cells whose centre lies clear of the holes count.
  const auto counted = [&](int ix, int iy) {
    const Eigen::Vector2d centre(-0.5 * t.board_width + (ix + 0.5) * cell, -0.5 * t.board_height + (iy + 0.5) * cell);
    for (const Eigen::Vector2d& h : t.hole_centers())
      if ((centre - h).norm() < t.hole_radius + cell) return false;
    return ix >= 0 && iy >= 0 && ix < nx && iy < ny;
  };
  int total = 0;
  for (int ix = 0; ix < nx; ++ix)
    for (int iy = 0; iy < ny; ++iy) total += counted(ix, iy);
  std::set<std::pair<int, int>> covered;
  std::array<int, 4> through{};
  double after_one_frame = 0.0;
  std::vector<SurfaceId> surfaces;
  for (std::uint64_t frame = 0; frame < 20; ++frame) {  // 2 s at 10 Hz
    const LidarCloud cloud = lidar.sweep(caster, Eigen::Isometry3d::Identity(), frame, &surfaces);
    for (std::size_t i = 0; i < cloud.size(); ++i) {
      const Eigen::Vector3d q = T_board * cloud.points[i];
      if (surfaces[i] == SurfaceId::Board && std::abs(q.z()) < 0.1) {
        const int ix = static_cast<int>(std::floor((q.x() + 0.5 * t.board_width) / cell));
        const int iy = static_cast<int>(std::floor((q.y() + 0.5 * t.board_height) / cell));
        if (counted(ix, iy)) covered.insert({ix, iy});
      }
      const int hole = caster.hole_on_front_plane(Eigen::Vector3d::Zero(), cloud.points[i].normalized());
      if (hole >= 0 && surfaces[i] != SurfaceId::Board) ++through[hole];
    }
    if (frame == 0) after_one_frame = static_cast<double>(covered.size()) / total;
  }
  const double coverage = static_cast<double>(covered.size()) / total;
  RecordProperty("coverage_after_2s", std::to_string(coverage));
  RecordProperty("coverage_after_0.1s", std::to_string(after_one_frame));
  EXPECT_GE(coverage, c.min_coverage);
  EXPECT_LE(after_one_frame, coverage);
  for (int h = 0; h < 4; ++h) EXPECT_GE(through[h], 40) << "hole " << h;
}

INSTANTIATE_TEST_SUITE_P(
    Models, RosetteCoverage,
    ::testing::Values(CoverageCase{"avia", 2.0, 0.99}, CoverageCase{"avia", 5.0, 0.99},
                      CoverageCase{"mid360", 2.0, 0.97}, CoverageCase{"mid360", 3.0, 0.93},
                      CoverageCase{"mid360", 5.0, 0.75}),
    [](const auto& info) {
      return info.param.model + "_" + std::to_string(static_cast<int>(info.param.distance)) + "m";
    });

}  // namespace
}  // namespace l2s::sim
