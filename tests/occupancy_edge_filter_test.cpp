// Hole rims of a dense, ring-free board cloud (a non-repetitive scan
// accumulated over a static board), found from the board's occupancy.

#include <l2s/circle_finder.hpp>
#include <l2s/error.hpp>
#include <l2s/occupancy_edge_filter.hpp>

#include "support/ring_scene.hpp"

#include <gtest/gtest.h>

#include <random>

namespace l2s {
namespace {

using test::board_pose;
using test::kDeg;
using test::Scene;

/// `count` rays in random directions of a cone around the board, as an
/// accumulated non-repetitive scan gives them, with range noise.
std::vector<Eigen::Vector3d> random_scan(const Scene& scene, int count, double noise, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  const Eigen::Vector3d axis = scene.T_sensor_board.translation().normalized();
  const double az0 = std::atan2(axis.y(), axis.x()), el0 = std::asin(axis.z());
  std::uniform_real_distribution<double> az(az0 - 20 * kDeg, az0 + 20 * kDeg), el(el0 - 15 * kDeg, el0 + 15 * kDeg);
  std::normal_distribution<double> range_noise(0.0, noise);
  std::vector<Eigen::Vector3d> points;
  for (int k = 0; k < count; ++k) {
    const Eigen::Vector3d d = test::ray(el(rng), az(rng));
    const double r = scene.cast(d);
    if (r != test::kNoHit) points.push_back(d * (r + range_noise(rng)));
  }
  return points;
}

std::vector<std::size_t> board_points(const std::vector<Eigen::Vector3d>& points, const Scene& scene) {
  std::vector<std::size_t> inliers;
  for (std::size_t i = 0; i < points.size(); ++i)
    if (std::abs(scene.visible_plane().signedDistance(points[i])) < 0.05) inliers.push_back(i);
  return inliers;
}

/// The filter with default params on `points`, the board's points taken as
/// those on the scene's visible plane.
OccupancyEdgeFilter::Result filter_board(const std::vector<Eigen::Vector3d>& points, const Scene& scene) {
  return OccupancyEdgeFilter().filter(points, scene.visible_plane(), board_points(points, scene),
                                      Eigen::Vector3d::UnitZ(), scene.target);
}

TEST(OccupancyEdgeFilter, FindsTheFourRimsOfADenseBoard) {
  Scene scene;
  scene.T_sensor_board = board_pose({3.5, 0.3, 0.1}, 20.0 * kDeg, 5.0 * kDeg);
  const auto points = random_scan(scene, 60000, 0.02, 1);
  const auto board = board_points(points, scene);
  const auto result = OccupancyEdgeFilter().filter(points, scene.visible_plane(), board, Eigen::Vector3d::UnitZ(),
                                                   scene.target);
  ASSERT_TRUE(result.found) << result.reason;
  EXPECT_EQ(result.holes, 4);
  EXPECT_GT(result.edges.size(), 4u * 40u);

  const auto circles = CircleFinder().find(result.edges, scene.visible_plane(), Eigen::Vector3d::UnitZ(),
                                           scene.target);
  ASSERT_TRUE(circles.found) << circles.reason;
  const HoleCenters truth = scene.true_centers();
  for (int h = 0; h < 4; ++h) EXPECT_LT((circles.centers[h] - truth[h]).norm(), 0.006) << "hole " << h;
}

TEST(OccupancyEdgeFilter, CompletesHolesCutByTheEdgeOfTheFieldOfView) {
  // A Mid-360 sees nothing below -7 deg: that edge runs through the lower
  // holes (0.06 m under their centres), which open onto the unscanned
  // outside. The two upper holes and the pattern's spacing say where they are.
  Scene scene;
  scene.T_sensor_board = board_pose({3.0, 0.2, 0.0}, 15.0 * kDeg);
  const double lowest = std::atan2(-0.2 - 0.06, 3.0);
  std::vector<Eigen::Vector3d> points;
  for (const Eigen::Vector3d& p : random_scan(scene, 80000, 0.02, 3))
    if (std::atan2(p.z(), p.head<2>().norm()) > lowest) points.push_back(p);
  const auto result = filter_board(points, scene);
  ASSERT_TRUE(result.found) << result.reason;
  EXPECT_EQ(result.holes, 4);
  const auto circles = CircleFinder().find(result.edges, scene.visible_plane(), Eigen::Vector3d::UnitZ(),
                                           scene.target);
  ASSERT_TRUE(circles.found) << circles.reason;
  const HoleCenters truth = scene.true_centers();
  for (int h = 0; h < 4; ++h) EXPECT_LT((circles.centers[h] - truth[h]).norm(), 0.006) << "hole " << h;
}

TEST(OccupancyEdgeFilter, SaysWhenTheFieldOfViewCutsTheBoardBeyondHoleCentres) {
  // The edge of the field of view runs 0.03 m above the lower holes' centres:
  // little more than a sliver of them is scanned, the pattern has too little
  // to complete them, and the user is told the board is cut, not only that
  // holes are missing. The whole board gives no such hint.
  Scene scene;
  scene.T_sensor_board = board_pose({3.0, 0.2, 0.0}, 15.0 * kDeg);
  const double lowest = std::atan2(-0.2 + 0.03, 3.0);
  std::vector<Eigen::Vector3d> points;
  for (const Eigen::Vector3d& p : random_scan(scene, 80000, 0.02, 3))
    if (std::atan2(p.z(), p.head<2>().norm()) > lowest) points.push_back(p);
  const auto cut = filter_board(points, scene);
  EXPECT_LT(cut.holes, 4);
  EXPECT_LT(cut.seen_height, scene.target.board_height - scene.target.hole_radius);
  EXPECT_NE(cut.cut_board_hint(scene.target).find("cuts it"), std::string::npos) << cut.cut_board_hint(scene.target);

  const auto whole_points = random_scan(scene, 80000, 0.02, 3);
  const auto whole = filter_board(whole_points, scene);
  EXPECT_EQ(whole.holes, 4);
  EXPECT_EQ(whole.cut_board_hint(scene.target), "");
}

TEST(OccupancyEdgeFilter, SparseBoardSaysWhy) {
  Scene scene;
  const auto points = random_scan(scene, 400, 0.02, 2);
  const auto result = filter_board(points, scene);
  EXPECT_FALSE(result.found);
  EXPECT_FALSE(result.reason.empty());
}

TEST(OccupancyEdgeFilter, ABoardScannedTooBrieflySaysToAccumulateLonger) {
  // A fifth of a second of a Mid-360 leaves a few hundred points on the
  // board: gaps between them as wide as the holes. The reason says so and
  // how much longer to scan, rather than only that no hole was found.
  Scene scene;
  const auto points = random_scan(scene, 400, 0.02, 4);
  const auto result = filter_board(points, scene);
  EXPECT_FALSE(result.found);
  EXPECT_NE(result.reason.find("accumulate at least"), std::string::npos) << result.reason;
  EXPECT_GT(result.sparse_factor, 1.0);
  // A densely scanned board never gets that advice.
  const auto dense = random_scan(scene, 60000, 0.02, 4);
  const auto found = filter_board(dense, scene);
  EXPECT_EQ(found.reason.find("accumulate at least"), std::string::npos) << found.reason;
  EXPECT_EQ(found.sparse_factor, 0.0);
}

TEST(OccupancyEdgeFilter, RejectsInvalidParamsNamingTheField) {
  OccupancyEdgeFilter::Params params;
  params.max_cell = 0.001;
  try {
    OccupancyEdgeFilter filter(params);
    FAIL() << "expected ParamError";
  } catch (const ParamError& e) {
    EXPECT_EQ(e.field(), "max_cell");
  }
}

}  // namespace
}  // namespace l2s
