// The lidar branch on the problems of real recordings (issue: real lidars):
// a side wall that looks board-sized, stray returns inside holes, holes that
// look smaller than target.yaml says. Each scene is scanned by the small ring
// caster of support/ring_scene.hpp and run through the branch exactly as
// Calibrator::add runs it (inspect_lidar).

#include <l2s/calibrator.hpp>
#include <l2s/frame_inspector.hpp>

#include "support/ring_scene.hpp"

#include <gtest/gtest.h>

#include <random>

namespace l2s {
namespace {

using test::board_pose;
using test::kDeg;
using test::Scene;

/// Largest distance between found and true centres [m].
double centre_error(const HoleCenters& found, const HoleCenters& truth) {
  double worst = 0.0;
  for (int h = 0; h < 4; ++h) worst = std::max(worst, (found[h] - truth[h]).norm());
  return worst;
}

/// The corridor of the issue: a 16-beam sweep, the board at ~3.3 m, side walls 1.3 m away.
Scene corridor() {
  Scene scene;
  scene.T_sensor_board = board_pose({3.3, 0.1, 0.0}, 10.0 * kDeg);
  scene.planes = {Plane(Eigen::Vector3d::UnitY(), -1.3), Plane(-Eigen::Vector3d::UnitY(), -1.3),
                  Plane(Eigen::Vector3d::UnitZ(), 1.2), Plane(Eigen::Vector3d::UnitX(), -9.0)};
  return scene;
}

TEST(LidarDetection, FindsTheBoardBetweenCorridorWalls) {
  const Scene scene = corridor();
  const auto params = Calibrator::Params::preset("default");
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const LidarInspection in = inspect_lidar(test::scan(scene, test::vlp16(), seed), scene.target, params);
    ASSERT_TRUE(in.report.found) << "seed " << seed << ": " << in.report.failed_stage << ": " << in.report.reason;
    EXPECT_LT(centre_error(in.report.centers, scene.true_centers()), 0.01) << "seed " << seed;
    // The walls were board-sized candidates too, and lost to the board.
    ASSERT_TRUE(in.plane.has_value());
    EXPECT_GE(in.plane->ranking.size(), 1u);
  }
}

TEST(LidarDetection, SideWallRanksBelowTheBoardAndFailsVerification) {
  const Scene scene = corridor();
  const LidarInspection in =
      inspect_lidar(test::scan(scene, test::vlp16(), 7), scene.target, Calibrator::Params::preset("default"));
  ASSERT_TRUE(in.report.found) << in.report.reason;
  for (const BoardHypothesis& h : in.hypotheses) {
    const PlaneCandidate& c = in.plane->candidates[h.candidate];
    const bool wall = std::abs(std::abs(c.plane.normal().y()) - 1.0) < 0.05;  // facing sideways
    EXPECT_FALSE(wall && h.chosen) << "a side wall was chosen: " << h.reason;
  }
}

TEST(LidarDetection, AWallWindowWithoutHolesIsRejectedByItsEvidence) {
  Scene scene = corridor();
  scene.has_board = false;
  const LidarInspection in =
      inspect_lidar(test::scan(scene, test::vlp16(), 8), scene.target, Calibrator::Params::preset("default"));
  EXPECT_FALSE(in.report.found);
  for (const BoardHypothesis& h : in.hypotheses) EXPECT_FALSE(h.verified) << h.reason;
}

/// Stray board-plane returns inside the holes next to their rims, as mixed
/// returns and hits on the hole's inner wall make them.
LidarCloud with_strays(const LidarCloud& sweep, const Scene& scene, std::uint64_t seed) {
  LidarCloud out = sweep;
  const Plane face = scene.visible_plane();
  const Eigen::Isometry3d T_board_sensor = scene.T_sensor_board.inverse();
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> coin(0.0, 1.0);
  for (std::size_t i = 0; i < out.size(); ++i) {
    const Eigen::Vector3d d = out.points[i].normalized();
    const double t = -face.offset() / face.normal().dot(d);
    if (t <= 0.0 || out.points[i].norm() < t + 0.3) continue;  // not seen through the board plane
    const Eigen::Vector2d q = (T_board_sensor * (t * d)).head<2>();
    for (const Eigen::Vector2d& c : scene.target.hole_centers()) {
      const double from_rim = scene.target.hole_radius - (q - c).norm();
      if (from_rim > 0.0 && from_rim < 0.02 && coin(rng) < 0.5) out.points[i] = (t + 0.005) * d;
    }
  }
  return out;
}

TEST(LidarDetection, StrayReturnsInsideHolesKeepEveryRing) {
  Scene scene;
  scene.T_sensor_board = board_pose({3.3, 0.2, 0.05}, 15.0 * kDeg);
  const auto params = Calibrator::Params::preset("default");
  const LidarCloud clean = test::scan(scene, test::vlp16(), 21);
  const LidarCloud stray = with_strays(clean, scene, 3);
  const LidarInspection a = inspect_lidar(clean, scene.target, params);
  const LidarInspection b = inspect_lidar(stray, scene.target, params);
  ASSERT_TRUE(a.report.found) << a.report.reason;
  ASSERT_TRUE(b.report.found) << b.report.reason;
  ASSERT_TRUE(b.discontinuities.has_value());
  EXPECT_GT(b.discontinuities->counts.stray_points, 0u);
  EXPECT_EQ(b.discontinuities->counts.rings_kept, a.discontinuities->counts.rings_kept);
  EXPECT_EQ(b.discontinuities->counts.rings_rejected, 0u);
  EXPECT_LT(centre_error(b.report.centers, scene.true_centers()), 0.015);
}

TEST(LidarDetection, ShrunkenHolesDoNotSlideTheCentres) {
  // The board as the lidar sees it has holes of 0.107 m; target.yaml says 0.12.
  Scene scene;
  scene.T_sensor_board = board_pose({3.0, -0.3, 0.1}, -20.0 * kDeg);
  scene.target.hole_radius = 0.107;
  const Target nominal;  // r = 0.12
  const auto params = Calibrator::Params::preset("default");
  std::vector<double> errors, radii;
  for (std::uint64_t seed = 31; seed < 36; ++seed) {
    const LidarInspection in = inspect_lidar(test::scan(scene, test::vlp16(), seed), nominal, params);
    ASSERT_TRUE(in.report.found) << in.report.reason;
    errors.push_back(centre_error(in.report.centers, scene.true_centers()));
    radii.push_back(in.report.hole_radius);
  }
  std::sort(errors.begin(), errors.end());
  for (double r : radii) EXPECT_NEAR(r, 0.107, 0.006);
  EXPECT_LT(errors[errors.size() / 2], 0.008);  // median over frames
}

/// `count` returns of a non-repetitive scan accumulated over a static scene
/// (ring-free): rays spread evenly over an elliptic field of view,
/// `half_azimuth` x `half_elevation` about the x axis (Livox Avia: 35.2 x
/// 38.6 deg), with 2 cm range noise. Rays that hit nothing give no point.
LidarCloud ring_free_scan(const Scene& scene, int count, double half_azimuth, double half_elevation,
                          std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::normal_distribution<double> noise(0.0, 0.02);
  LidarCloud cloud;
  while (static_cast<int>(cloud.size()) < count) {
    const double a = unit(rng), e = unit(rng);
    if (a * a + e * e > 1.0) continue;
    const Eigen::Vector3d d = test::ray(e * half_elevation, a * half_azimuth);
    const double r = scene.cast(d);
    if (r == test::kNoHit) continue;
    cloud.points.push_back(d * (r + noise(rng)));
  }
  return cloud;
}

TEST(LidarDetection, RingFreeBoardCutByTheFieldOfViewIsFound) {
  // The Avia's field of view ends at 35.2 deg: it cuts the board 0.3 m from
  // its centre, through a hole column. The board patch in view is 1.0 m
  // long, not 1.4, and two of the holes open onto the unscanned outside.
  Scene scene;
  const double distance = 3.5, azimuth = (35.2 - 4.9) * kDeg;
  scene.T_sensor_board = board_pose({distance * std::cos(azimuth), distance * std::sin(azimuth), 0.1});
  const LidarCloud cloud = ring_free_scan(scene, 150000, 35.2 * kDeg, 38.6 * kDeg, 5);
  const LidarInspection in = inspect_lidar(cloud, scene.target, Calibrator::Params::preset("default"));
  EXPECT_TRUE(in.ring_free);
  ASSERT_TRUE(in.report.found) << in.report.failed_stage << ": " << in.report.reason;
  EXPECT_LT(centre_error(in.report.centers, scene.true_centers()), 0.005);
}

TEST(LidarDetection, RingFreeShrunkenHolesDoNotSlideTheCentres) {
  // An accumulated Mid-360 cloud of a real board showed holes of 0.107-0.109 m
  // where target.yaml says 0.12; a fixed-radius fit slid the centres ~4 cm.
  Scene scene;
  scene.T_sensor_board = board_pose({3.2, -0.4, 0.2}, -20.0 * kDeg, 5.0 * kDeg);
  scene.target.hole_radius = 0.107;
  const Target nominal;  // r = 0.12
  const LidarCloud cloud = ring_free_scan(scene, 150000, 35.2 * kDeg, 38.6 * kDeg, 6);
  const LidarInspection in = inspect_lidar(cloud, nominal, Calibrator::Params::preset("default"));
  ASSERT_TRUE(in.report.found) << in.report.failed_stage << ": " << in.report.reason;
  EXPECT_NEAR(in.report.hole_radius, 0.107, 0.006);
  EXPECT_LT(centre_error(in.report.centers, scene.true_centers()), 0.005);
}

TEST(LidarDetection, AWindowOfRingFreeSweepsIsNotClassifiedAgain) {
  // The Calibrator found each sweep ring-free; their accumulation, cropped by
  // the pass-through to the board's surroundings, can still show scan lines
  // (a real Avia window in a random scene: 9 lines). The window is ring-free as
  // its sweeps were: here, sweeps of a 64-beam scan without a ring field.
  Scene scene;
  std::vector<LidarCloud> sweeps;
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    LidarCloud sweep = test::scan(scene, test::beams64(), seed);
    sweep.ring.clear();
    sweeps.push_back(sweep);
  }
  const LidarInspection in = inspect_lidar(sweeps, scene.target, Calibrator::Params::preset("default"));
  EXPECT_TRUE(in.ring_free);
  EXPECT_TRUE(in.occupancy.has_value());
  EXPECT_FALSE(in.discontinuities.has_value());
}

}  // namespace
}  // namespace l2s
