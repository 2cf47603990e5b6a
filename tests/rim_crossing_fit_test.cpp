// The hole pattern of a static pose fitted to its rings' rim crossings
// (circles/rim_crossing_fit.hpp). A spinning lidar's rings cross each rim
// somewhere inside one azimuth step; over several sweeps, with the step's
// phase changing from sweep to sweep, the intervals pin the pattern far more
// sharply than their midpoints' average does.

#include "circles/rim_crossing_fit.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace l2s {
namespace {

constexpr double kDeg = M_PI / 180.0;

/// A board squarely facing a ring lidar (x forward, z up) `range` ahead,
/// its holes at `centres` (sensor frame, on the plane x = range).
struct FacingBoard {
  double range = 3.5;
  HoleCenters centres;
  Plane plane{Eigen::Vector3d(-1.0, 0.0, 0.0), 3.5};  // normal towards the sensor

  explicit FacingBoard(const Target& target, const Eigen::Vector2d& shift) {
    plane = Plane(Eigen::Vector3d(-1.0, 0.0, 0.0), range);
    const auto holes = target.hole_centers();
    for (int h = 0; h < 4; ++h)
      centres[h] = Eigen::Vector3d(range, -holes[h].x() + shift.x(), holes[h].y() + shift.y());
  }

  Eigen::Vector3d hit(double elevation, double azimuth) const {
    const Eigen::Vector3d d(std::cos(elevation) * std::cos(azimuth), std::cos(elevation) * std::sin(azimuth),
                            std::sin(elevation));
    return d * (range / d.x());
  }
  bool in_hole(const Eigen::Vector3d& p, double radius) const {
    for (const Eigen::Vector3d& c : centres)
      if ((p - c).norm() < radius) return true;
    return false;
  }
};

/// The crossings of `sweeps` VLP-16-like sweeps (rings 2 deg apart, 0.2 deg
/// azimuth steps, a random phase per sweep) through a thin board's holes.
std::vector<RimCrossing> crossings_of(const FacingBoard& board, double radius, int sweeps, std::mt19937& rng) {
  std::vector<RimCrossing> out;
  std::uniform_real_distribution<double> phase(0.0, 0.2 * kDeg);
  for (int s = 0; s < sweeps; ++s) {
    const double offset = phase(rng);
    for (int ring = -15; ring <= 15; ring += 2) {
      const double elevation = ring * kDeg;
      Eigen::Vector3d previous = board.hit(elevation, -20.0 * kDeg + offset);
      for (int a = 1; a < 200; ++a) {
        const Eigen::Vector3d p = board.hit(elevation, (-20.0 + 0.2 * a) * kDeg + offset);
        const bool was = board.in_hole(previous, radius), is = board.in_hole(p, radius);
        if (was != is) out.push_back(was ? RimCrossing{p, previous} : RimCrossing{previous, p});
        previous = p;
      }
    }
  }
  return out;
}

detail::RimCrossingFitParams thin_board() {
  detail::RimCrossingFitParams params;
  params.model_thickness = false;
  return params;
}

TEST(RimCrossingFit, PinsThePatternInsideTheAzimuthSteps) {
  const Target target;
  const FacingBoard board(target, Eigen::Vector2d(0.013, -0.021));
  std::mt19937 rng(5);
  const std::vector<RimCrossing> crossings = crossings_of(board, target.hole_radius, 20, rng);
  ASSERT_GT(crossings.size(), 80u);
  // Start as a clustered estimate would be: a few millimetres off, turned.
  HoleCenters start;
  const Eigen::AngleAxisd turn(0.3 * kDeg, Eigen::Vector3d::UnitX());
  const Eigen::Vector3d middle = 0.25 * (board.centres[0] + board.centres[1] + board.centres[2] + board.centres[3]);
  for (int h = 0; h < 4; ++h)
    start[h] = middle + turn * (board.centres[h] - middle) + Eigen::Vector3d(0, 0.003, -0.002);

  const detail::RimCrossingFit fit =
      detail::fit_pattern_to_rim_crossings(start, board.plane, crossings, target, thin_board());
  ASSERT_TRUE(fit.centers) << fit.reason;
  // 0.03-0.05 mm off; the midpoints alone (midpoint_weight 1e6): 0.11-0.27 mm.
  for (int h = 0; h < 4; ++h) EXPECT_LT(((*fit.centers)[h] - board.centres[h]).norm(), 0.0001) << hole_name(Hole(h));
  EXPECT_NEAR(fit.radius, target.hole_radius, 0.0002);
  EXPECT_EQ(fit.crossings, static_cast<int>(crossings.size()));
}

// A beam footprint makes a real lidar's holes look smaller (the
// simulator's: 115.5 of 120 mm at 3-4 m). The fit measures that radius, and
// the registration trusts its centres tightly only within 1 % of the
// target's (detail::lidar_centres_sharp).
TEST(RimCrossingFit, MeasuresHolesThatLookSmallerThanTheTargetsAsSuch) {
  const Target target;
  const FacingBoard board(target, Eigen::Vector2d(0.004, 0.011));
  std::mt19937 rng(9);
  const double seen = target.hole_radius - 0.0045;
  const std::vector<RimCrossing> crossings = crossings_of(board, seen, 20, rng);
  const detail::RimCrossingFit fit =
      detail::fit_pattern_to_rim_crossings(board.centres, board.plane, crossings, target, thin_board());
  ASSERT_TRUE(fit.centers) << fit.reason;
  EXPECT_NEAR(fit.radius, seen, 0.0005);
  EXPECT_LT(fit.radius / target.hole_radius, 0.99);
}

TEST(RimCrossingFit, LeavesOutACrossingNoRimCanSatisfy) {
  const Target target;
  const FacingBoard board(target, Eigen::Vector2d::Zero());
  std::mt19937 rng(6);
  std::vector<RimCrossing> crossings = crossings_of(board, target.hole_radius, 10, rng);
  // A mixed return: a "board" return 3 cm inside the top-left hole.
  const Eigen::Vector3d inside = board.centres[0] + Eigen::Vector3d(0, 0.0, target.hole_radius - 0.03);
  crossings.push_back({inside, inside + Eigen::Vector3d(0, 0.012, 0)});
  const detail::RimCrossingFit fit =
      detail::fit_pattern_to_rim_crossings(board.centres, board.plane, crossings, target, thin_board());
  ASSERT_TRUE(fit.centers) << fit.reason;
  EXPECT_EQ(fit.crossings, static_cast<int>(crossings.size()) - 1);
  for (int h = 0; h < 4; ++h) EXPECT_LT(((*fit.centers)[h] - board.centres[h]).norm(), 0.0005);
}

TEST(RimCrossingFit, SaysWhyWhenTooFewCrossingsPinThePattern) {
  const Target target;
  const FacingBoard board(target, Eigen::Vector2d::Zero());
  std::mt19937 rng(7);
  std::vector<RimCrossing> crossings = crossings_of(board, target.hole_radius, 1, rng);
  crossings.resize(3);
  const detail::RimCrossingFit fit =
      detail::fit_pattern_to_rim_crossings(board.centres, board.plane, crossings, target, thin_board());
  EXPECT_FALSE(fit.centers);
  EXPECT_NE(fit.reason.find("rim crossings"), std::string::npos) << fit.reason;
}

TEST(RimCrossingFit, RefusesCentresThatAreNotThePattern) {
  const Target target;
  const FacingBoard board(target, Eigen::Vector2d::Zero());
  std::mt19937 rng(8);
  const std::vector<RimCrossing> crossings = crossings_of(board, target.hole_radius, 3, rng);
  HoleCenters swapped = board.centres;
  std::swap(swapped[0], swapped[3]);  // labels of a diagonal swapped: no rigid motion of the pattern
  const detail::RimCrossingFit fit =
      detail::fit_pattern_to_rim_crossings(swapped, board.plane, crossings, target, thin_board());
  EXPECT_FALSE(fit.centers);
}

}  // namespace
}  // namespace l2s
