// Whether a sweep has scan lines at all, and when its recovered rings deserve
// a warning: rosette (Livox-like) and evenly spread elevations are ring-free;
// starved rings, rings closer than their width, too many rings for the
// returns and returns spread between the rings are doubtful.
#include <l2s/io/ring_recovery.hpp>

#include "lidar/rings/ring_report.hpp"
#include "support/laser_sweep.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace l2s::io {
namespace {

constexpr double kDeg = M_PI / 180.0;

// Range from the origin along unit `d` to a 8 x 6 x 2.7 m room around the sensor.
double room_range(const Eigen::Vector3d& d) {
  double best = 1e9;
  const double bounds[3][2] = {{-3.0, 5.0}, {-3.0, 3.0}, {-1.2, 1.5}};
  for (int axis = 0; axis < 3; ++axis)
    for (double wall : bounds[axis])
      if (d[axis] * wall > 0.0) best = std::min(best, wall / d[axis]);
  return best;
}

Eigen::Vector3d direction(double azimuth, double elevation) {
  return {std::cos(elevation) * std::cos(azimuth), std::cos(elevation) * std::sin(azimuth),
          std::sin(elevation)};
}

// A Livox Avia-like non-repetitive scan: a rose curve rho = R cos(k phi) in
// (azimuth, elevation), turned a little further with every petal, so that the
// pattern fills the 70 deg field of view instead of repeating.
LidarCloud rosette(int points, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, 0.01);
  LidarCloud cloud;
  const double radius = 35.0 * kDeg, k = 5.0, step = 0.0021, precession = 0.00037;
  for (int i = 0; i < points; ++i) {
    const double phi = i * step, rho = radius * std::cos(k * phi), turn = phi + i * precession;
    const Eigen::Vector3d d = direction(rho * std::cos(turn), rho * std::sin(turn));
    cloud.points.push_back((room_range(d) + noise(rng)) * d);
  }
  return cloud;
}

// A Mid-360-like sweep: full circle in azimuth, elevations spread evenly over
// -7..52 deg (quasi-random, no two returns at one elevation).
LidarCloud even_elevations(int points) {
  LidarCloud cloud;
  const double golden = 0.6180339887498949;
  for (int i = 0; i < points; ++i) {
    const double elevation = (-7.0 + 59.0 * std::fmod(i * golden, 1.0)) * kDeg;
    const double azimuth = 2.0 * M_PI * std::fmod(i * 0.7548776662466927, 1.0);
    const Eigen::Vector3d d = direction(azimuth, elevation);
    cloud.points.push_back(room_range(d) * d);
  }
  return cloud;
}

TEST(ScanStructure, RosetteScanIsRingFree) {
  LidarCloud cloud = rosette(40000, 3);
  const RingRecoveryReport report = recover_ring_structure(cloud);
  EXPECT_EQ(report.structure, ScanStructure::RingFree) << report.summary();
  EXPECT_FALSE(report.structure_reason.empty());
  EXPECT_EQ(cloud.ring.size(), cloud.size());
  const ScanClassification scan = classify_scan(rosette(40000, 3));
  EXPECT_EQ(scan.structure, ScanStructure::RingFree) << scan.reason;
}

TEST(ScanStructure, EvenlySpreadElevationsAreRingFree) {
  LidarCloud cloud = even_elevations(30000);
  const RingRecoveryReport report = recover_ring_structure(cloud);
  EXPECT_EQ(report.structure, ScanStructure::RingFree) << report.summary();
}

TEST(ScanStructure, SpinningLidarsHaveRings) {
  for (const test::LaserTable& table : {test::vlp16_table(), test::hdl64e_table()}) {
    const test::LaserSweep sweep = test::laser_sweep(table, {});
    const ScanClassification scan = classify_scan(sweep.cloud);
    EXPECT_EQ(scan.structure, ScanStructure::Rings) << table.name << ": " << scan.reason;
    test::OrganisedSweep corridor = test::corridor_sweep(table, {});
    const RingRecoveryReport report = recover_ring_structure(corridor.cloud);
    EXPECT_EQ(report.structure, ScanStructure::Rings) << table.name << ": " << report.summary();
    EXPECT_FALSE(report.doubtful) << table.name << ": " << report.summary();
  }
  LidarCloud with_field;
  with_field.points.emplace_back(1.0, 0.0, 0.0);
  with_field.ring.push_back(3);
  EXPECT_EQ(classify_scan(with_field).structure, ScanStructure::Rings);
}

// A laser that returned only a few times next to lasers with hundreds.
TEST(ScanStructure, StarvedRingIsDoubtful) {
  test::LaserSweep sweep = test::laser_sweep(test::vlp16_table(), {});
  LidarCloud cloud;
  int kept = 0;
  for (std::size_t i = 0; i < sweep.cloud.size(); ++i) {
    const Eigen::Vector3d& p = sweep.cloud.points[i];
    if (sweep.truth[i] == 9 && (kept >= 6 || !(std::hypot(p.x(), p.y()) > 1.5))) continue;
    kept += sweep.truth[i] == 9;
    cloud.points.push_back(p);
  }
  const RingRecoveryReport report = recover_ring_structure(cloud);
  EXPECT_EQ(report.rings, 16) << report.summary();
  EXPECT_TRUE(report.doubtful);
  EXPECT_NE(report.doubt.find("ring 9 has 6 returns"), std::string::npos) << report.doubt;
  EXPECT_EQ(report.min_points, 6u);
}

TEST(ScanStructure, TooManyRingsForTheReturnsIsDoubtful) {
  test::SweepOptions options;
  options.points_per_laser = 6;
  options.min_range = 3.0;
  options.invalid_points = 0;
  test::LaserSweep sweep = test::laser_sweep(test::vlp16_table(), options);
  const RingRecoveryReport report = recover_ring_structure(sweep.cloud);
  EXPECT_EQ(report.rings, 16) << report.summary();
  EXPECT_TRUE(report.doubtful);
  EXPECT_NE(report.doubt.find("returns a ring"), std::string::npos) << report.doubt;
}

// Scan lines blurred over half their spacing: still rings, but the elevations
// between them fill up.
TEST(ScanStructure, ReturnsSpreadBetweenRingsAreDoubtful) {
  test::SweepOptions options;
  options.jitter_deg = 0.45;
  options.min_range = 2.0;
  test::LaserSweep sweep = test::laser_sweep(test::vlp16_table(), options);
  const RingRecoveryReport report = recover_ring_structure(sweep.cloud);
  EXPECT_EQ(report.structure, ScanStructure::Rings) << report.summary();
  EXPECT_TRUE(report.doubtful);
  EXPECT_NE(report.doubt.find("spread between the rings"), std::string::npos) << report.doubt;
  EXPECT_LT(report.contrast, 5.0);
  EXPECT_GT(report.contrast, 2.0);
}

// Two lasers 0.3 deg apart whose returns spread 0.08 deg: two rings, with far
// more returns near the middle between them than other rings have.
TEST(ScanStructure, MeasuresHowCloseRingsCrowdEachOther) {
  std::mt19937 rng(8);
  std::normal_distribution<double> jitter(0.0, 0.08 * kDeg);
  std::uniform_real_distribution<double> azimuth(-M_PI, M_PI), range(2.0, 30.0);
  LidarCloud cloud;
  for (double elevation : {-10.0, -5.0, 0.0, 0.3, 5.0, 10.0})
    for (int i = 0; i < 1000; ++i)
      cloud.points.push_back(range(rng) * direction(azimuth(rng), elevation * kDeg + jitter(rng)));
  const RingRecoveryReport report = recover_ring_structure(cloud);
  ASSERT_EQ(report.lasers.size(), 6u) << report.summary();
  for (int k : {2, 3}) EXPECT_LT(report.lasers[k].contrast, 10.0) << k;
  for (int k : {0, 1, 4, 5}) EXPECT_GT(report.lasers[k].contrast, 100.0) << k;
}

// The doubt itself: a ring with as many returns next to the middle to its
// neighbour as on itself overlaps it.
TEST(ScanStructure, OverlappingRingsAreDoubtful) {
  RingRecoveryReport report;
  for (int k = 0; k < 8; ++k)
    report.lasers.push_back(
        {k, (-10.0 + 2.0 * k) * kDeg, 0.0, 0.02 * kDeg, 500, k == 5 ? 2.5 : 80.0});
  report.rings = 8;
  report.points = 4000;
  report.contrast = 60.0;
  finish_report(report);
  EXPECT_EQ(report.structure, ScanStructure::Rings);
  EXPECT_TRUE(report.doubtful);
  EXPECT_NE(report.doubt.find("ring 5 overlaps a neighbour (contrast 2.5"), std::string::npos)
      << report.doubt;
}

TEST(ScanStructure, SummaryNamesSourceRingsAndDoubts) {
  test::LaserSweep sweep = test::laser_sweep(test::vlp16_table(), {});
  const RingRecoveryReport report = recover_ring_structure(sweep.cloud);
  const std::string summary = report.summary();
  EXPECT_NE(summary.find("laser model: 16 rings"), std::string::npos) << summary;
  EXPECT_NE(summary.find("rings: 16 scan lines"), std::string::npos) << summary;
  EXPECT_EQ(summary.find("DOUBTFUL"), std::string::npos) << summary;
  EXPECT_EQ(to_string(RingSource::OrganisedRows), "organised rows");
  EXPECT_EQ(to_string(ScanStructure::RingFree), "ring-free");
}

}  // namespace
}  // namespace l2s::io
