#include <l2s/discontinuity_filter.hpp>
#include <l2s/error.hpp>

#include "support/ring_scene.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace l2s {
namespace {

using test::board_pose;
using test::kDeg;
using test::Scene;

/// Board points of a sweep by ground truth: near the visible face, inside the outline.
std::vector<std::size_t> true_board_points(const LidarCloud& cloud, const Scene& scene) {
  const Plane face = scene.visible_plane();
  std::vector<std::size_t> inliers;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const Eigen::Vector3d& p = cloud.points[i];
    if (!p.allFinite() || std::abs(face.signedDistance(p)) > 0.05) continue;
    const Eigen::Vector3d b = scene.T_sensor_board.inverse() * p;
    if (std::abs(b.x()) <= scene.target.board_width / 2 + 0.01 && std::abs(b.y()) <= scene.target.board_height / 2 + 0.01)
      inliers.push_back(i);
  }
  return inliers;
}

/// Distance of an edge point from the nearest hole rim, in the board plane.
double rim_distance(const Eigen::Vector3d& p, const Scene& scene) {
  const Eigen::Vector3d b = scene.T_sensor_board.inverse() * p;
  double best = 1e9;
  for (const Eigen::Vector2d& c : scene.target.hole_centers())
    best = std::min(best, std::abs((b.head<2>() - c).norm() - scene.target.hole_radius));
  return best;
}

DiscontinuityFilter::Result run(const LidarCloud& cloud, const Scene& scene, DiscontinuityFilter::Params params = {}) {
  return DiscontinuityFilter(params).filter(cloud, scene.visible_plane(), true_board_points(cloud, scene));
}

std::vector<std::array<double, 3>> sorted_edges(const DiscontinuityFilter::Result& r) {
  std::vector<std::array<double, 3>> out;
  for (const auto& e : r.edges) out.push_back({e.x(), e.y(), e.z()});
  std::sort(out.begin(), out.end());
  return out;
}

TEST(DiscontinuityFilter, MarksHoleEdgesOnRingsCrossingHoles) {
  const Scene scene;
  const LidarCloud sweep = test::scan(scene, test::vlp16(), 11);
  const auto result = run(sweep, scene);
  ASSERT_TRUE(result.found) << result.reason;
  // As many edges as rays truly leave the board into a hole (two per crossing).
  const std::size_t crossings = test::exact_hole_edges(scene, test::vlp16()).size();
  ASSERT_GE(crossings, 16u);  // >= 2 rings per hole
  EXPECT_EQ(result.edges.size(), crossings);
  EXPECT_EQ(result.counts.rings_kept * 4, crossings);  // at 3 m every such ring crosses two holes
  // Each ring on the board leaves it at both ends: those border points are dropped.
  EXPECT_EQ(result.counts.border_points, 2 * result.counts.rings);
  const double step = 3.0 * 0.2 * kDeg;  // one azimuth step at the board's range
  for (const auto& e : result.edges) EXPECT_LT(rim_distance(e, scene), 1.5 * step + 0.01);
  EXPECT_EQ(result.rings.size(), result.edges.size());
}

TEST(DiscontinuityFilter, ShuffledOrderGivesTheSameEdges) {
  const Scene scene;
  const LidarCloud sweep = test::scan(scene, test::vlp16(), 12);
  const auto a = run(sweep, scene);
  const auto b = run(test::shuffled(sweep, 99), scene);
  ASSERT_TRUE(a.found);
  EXPECT_EQ(sorted_edges(a), sorted_edges(b));
}

TEST(DiscontinuityFilter, IgnoresNaNPoints) {
  const Scene scene;
  test::RingScanner scanner = test::vlp16();
  const auto plain = run(test::scan(scene, scanner, 13), scene);
  scanner.nan_for_no_return = true;  // same rays, plus a NaN for every ray into the sky
  const LidarCloud with_nan = test::shuffled(test::scan(scene, scanner, 13), 5);
  ASSERT_GT(with_nan.size(), test::scan(scene, test::vlp16(), 13).size());
  const auto result = run(with_nan, scene);
  ASSERT_TRUE(result.found) << result.reason;
  EXPECT_EQ(sorted_edges(plain), sorted_edges(result));
}

TEST(DiscontinuityFilter, MissingReturnsBehindHolesAreEdges) {
  Scene scene;
  scene.planes = {Plane(Eigen::Vector3d::UnitZ(), 1.0)};  // ground only: sky through the holes
  const auto result = run(test::scan(scene, test::vlp16(), 14), scene);
  ASSERT_TRUE(result.found) << result.reason;
  EXPECT_EQ(result.edges.size(), test::exact_hole_edges(scene, test::vlp16()).size());
}

TEST(DiscontinuityFilter, HandlesBoardAcrossTheAzimuthWrap) {
  Scene scene;  // behind the sensor: the board straddles azimuth +-180 deg
  scene.T_sensor_board = board_pose({-3.0, 0.05, 0.03});
  scene.planes.push_back(Plane(Eigen::Vector3d::UnitX(), 6.0));
  const auto result = run(test::scan(scene, test::vlp16(), 15), scene);
  ASSERT_TRUE(result.found) << result.reason;
  EXPECT_EQ(result.edges.size(), test::exact_hole_edges(scene, test::vlp16()).size());
  EXPECT_EQ(result.counts.border_points, 2 * result.counts.rings);
}

TEST(DiscontinuityFilter, MidpointEdgesLieOnThePlaneNearerTheRim) {
  const Scene scene;
  const LidarCloud sweep = test::scan(scene, test::vlp16(), 16);
  const auto mid = run(sweep, scene);
  const auto last = run(sweep, scene, DiscontinuityFilter::Params::paper());
  ASSERT_EQ(mid.edges.size(), last.edges.size());
  double mid_error = 0.0, last_error = 0.0;
  for (std::size_t i = 0; i < mid.edges.size(); ++i) {
    EXPECT_NEAR(scene.visible_plane().absDistance(mid.edges[i]), 0.0, 1e-9);
    mid_error += rim_distance(mid.edges[i], scene);
    last_error += rim_distance(last.edges[i], scene);
  }
  EXPECT_LT(mid_error, last_error);
}

TEST(DiscontinuityFilter, ReportsMissingRings) {
  const Scene scene;
  LidarCloud sweep = test::scan(scene, test::vlp16(), 17);
  sweep.ring.clear();
  const auto result = DiscontinuityFilter().filter(sweep, scene.visible_plane(), {});
  EXPECT_FALSE(result.found);
  EXPECT_NE(result.reason.find("ring"), std::string::npos);
}

// The contract: bad data is a reason in the result; bad arguments throw ParamError.
TEST(DiscontinuityFilter, NonFinitePlaneGivesReasonAndBadArgumentsThrow) {
  const Scene scene;
  LidarCloud sweep = test::scan(scene, test::vlp16(), 17);
  const auto inliers = true_board_points(sweep, scene);
  const Plane nan_plane(Eigen::Vector3d(std::nan(""), 0.0, 1.0), 3.0);
  DiscontinuityFilter::Result result;
  EXPECT_NO_THROW(result = DiscontinuityFilter().filter(sweep, nan_plane, inliers));
  EXPECT_FALSE(result.found);
  EXPECT_NE(result.reason.find("not finite"), std::string::npos) << result.reason;
  EXPECT_THROW(DiscontinuityFilter().filter(sweep, scene.visible_plane(), {sweep.size()}), ParamError);
  sweep.ring.pop_back();
  EXPECT_THROW(DiscontinuityFilter().filter(sweep, scene.visible_plane(), inliers), ParamError);
}

TEST(DiscontinuityFilter, RejectsInvalidParamsNamingTheField) {
  DiscontinuityFilter::Params params;
  params.max_ring_edges = 1;
  try {
    DiscontinuityFilter filter(params);
    FAIL() << "expected ParamError";
  } catch (const ParamError& e) {
    EXPECT_EQ(e.field(), "max_ring_edges");
  }
}

}  // namespace
}  // namespace l2s
