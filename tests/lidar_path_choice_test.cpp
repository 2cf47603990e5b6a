// Which lidar path a cloud takes is chosen from its returns, not from the
// presence of a ring field: an accumulated solid-state cloud cropped around
// the board goes the ring-free way whatever its file says (no ring field, a
// constant one, a line number that does not follow elevation), while a
// spinning lidar keeps its rings, from a good field or from its returns.
#include <l2s/calibrator.hpp>
#include <l2s/frame_inspector.hpp>
#include <l2s/io/ring_recovery.hpp>
#include <l2s/sim/simulation.hpp>

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

namespace l2s {
namespace {

/// The default board (1.4 x 1.0 m, holes r 0.12 m on 0.50 x 0.40 m) 2.5 m
/// ahead, squarely facing the lidar and leaning back 15 deg, as users of a
/// solid-state lidar keep a static board: returns integrated over seconds and
/// cropped around the board. Every point of its face is hit evenly (a rosette
/// over seconds), with 1.5 cm of range noise.
struct LeaningBoard {
  Target target;
  Eigen::Isometry3d T_lidar_board = Eigen::Isometry3d::Identity();
  LidarCloud cloud;

  explicit LeaningBoard(std::size_t returns) {
    Eigen::Matrix3d facing;  // board x right, y up, z towards the lidar
    facing.col(0) = -Eigen::Vector3d::UnitY();
    facing.col(1) = Eigen::Vector3d::UnitZ();
    facing.col(2) = -Eigen::Vector3d::UnitX();
    T_lidar_board.linear() = facing * Eigen::AngleAxisd(-15.0 * M_PI / 180.0, Eigen::Vector3d::UnitX()).matrix();
    T_lidar_board.translation() = Eigen::Vector3d(2.5, 0.2, 0.1);
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> x(-0.5 * target.board_width, 0.5 * target.board_width);
    std::uniform_real_distribution<double> y(-0.5 * target.board_height, 0.5 * target.board_height);
    std::normal_distribution<double> range_noise(0.0, 0.015);
    const auto holes = target.hole_centers();
    while (cloud.size() < returns) {
      const Eigen::Vector2d on_board(x(rng), y(rng));
      const bool in_hole = std::any_of(holes.begin(), holes.end(), [&](const Eigen::Vector2d& centre) {
        return (on_board - centre).norm() < target.hole_radius;
      });
      if (in_hole) continue;
      const Eigen::Vector3d p = T_lidar_board * Eigen::Vector3d(on_board.x(), on_board.y(), 0.0);
      cloud.points.push_back(p * (1.0 + range_noise(rng) / p.norm()));
    }
  }

  /// The largest distance from a found centre to the nearest true one.
  double worst_centre_error(const HoleCenters& found) const {
    double worst = 0.0;
    for (const Eigen::Vector3d& centre : found) {
      double nearest = std::numeric_limits<double>::infinity();
      for (const Eigen::Vector2d& hole : target.hole_centers())
        nearest = std::min(nearest, (centre - T_lidar_board * Eigen::Vector3d(hole.x(), hole.y(), 0.0)).norm());
      worst = std::max(worst, nearest);
    }
    return worst;
  }
};

void expect_detected_ring_free(const LeaningBoard& board, const LidarCloud& cloud, double tolerance = 0.005) {
  const LidarInspection in = inspect_lidar(cloud, board.target, Calibrator::Params::preset("default"));
  EXPECT_TRUE(in.ring_free);
  ASSERT_TRUE(in.report.found) << in.report.failed_stage << ": " << in.report.reason;
  EXPECT_LT(board.worst_centre_error(in.report.centers), tolerance);
}

TEST(LidarPathChoice, AnAccumulatedCloudWithoutARingFieldIsRingFree) {
  // A leaning board's returns all fit one laser model z = d tan(e) + h: ring
  // recovery finds one or two "lasers" for tens of thousands of returns, no
  // spinning lidar's sweep.
  const LeaningBoard board(40000);
  const io::ScanClassification scan = io::classify_scan(board.cloud);
  EXPECT_EQ(scan.structure, io::ScanStructure::RingFree) << scan.reason;
  expect_detected_ring_free(board, board.cloud);
}

TEST(LidarPathChoice, OneCroppedSweepOfTheLeaningBoardIsRingFreeToo) {
  // A tenth of a second of a Mid-360 on the board: a few thousand returns
  // on one "line" are no spinning lidar's sweep either. One sweep places
  // the holes to a centimetre; the calibrator accumulates a window of them.
  const LeaningBoard board(4000);
  const io::ScanClassification scan = io::classify_scan(board.cloud);
  EXPECT_EQ(scan.structure, io::ScanStructure::RingFree) << scan.reason;
  expect_detected_ring_free(board, board.cloud, 0.015);
}

TEST(LidarPathChoice, ARingFieldOfConstantValueIsNotOneLaser) {
  const LeaningBoard board(40000);
  LidarCloud cloud = board.cloud;
  cloud.ring.assign(cloud.size(), 0);
  const io::RingFieldCheck field = io::check_ring_field(cloud);
  EXPECT_FALSE(field.usable);
  EXPECT_NE(field.reason.find("1 value(s) for 40000 returns"), std::string::npos) << field.reason;
  expect_detected_ring_free(board, cloud);
}

TEST(LidarPathChoice, ALineNumberThatDoesNotFollowElevationIsNoRingField) {
  // A Livox `line` field: each of its six lasers draws the whole field of
  // view, so every value covers every elevation of the board.
  const LeaningBoard board(40000);
  LidarCloud cloud = board.cloud;
  for (std::size_t i = 0; i < cloud.size(); ++i) cloud.ring.push_back(static_cast<std::uint16_t>(i % 6));
  EXPECT_FALSE(io::check_ring_field(cloud).usable);
  expect_detected_ring_free(board, cloud);
}

/// A VLP-16 sweep of the paper's first setting, ring field as its driver writes it.
LidarCloud vlp16_sweep() {
  auto config = sim::SimulationConfig::paper(1, "vlp16");
  config.frames = 1;
  return sim::DatasetSimulator(config).sweep(0);
}

TEST(LidarPathChoice, ASpinningLidarsRingFieldIsKept) {
  const LidarCloud sweep = vlp16_sweep();
  ASSERT_TRUE(sweep.has_ring());
  const io::RingFieldCheck field = io::check_ring_field(sweep);
  EXPECT_TRUE(field.usable) << field.reason;
  // Numbered from the top (as some drivers do), the field still gives the lines.
  LidarCloud from_top = sweep;
  for (auto& ring : from_top.ring) ring = static_cast<std::uint16_t>(15 - ring);
  EXPECT_TRUE(io::check_ring_field(from_top).usable) << io::check_ring_field(from_top).reason;
  EXPECT_EQ(io::classify_scan(sweep).structure, io::ScanStructure::Rings);
}

TEST(LidarPathChoice, ASpinningLidarWithAFieldInFiringOrderHasItsRingsFromItsReturns) {
  // A VLP-16 fires its lasers interleaved (-15, 1, -13, 3, ... deg): a raw
  // laser id does not follow elevation. The field is dropped and the returns
  // give the 16 rings.
  LidarCloud sweep = vlp16_sweep();
  for (auto& ring : sweep.ring) ring = static_cast<std::uint16_t>(ring < 8 ? 2 * ring : 2 * (ring - 8) + 1);
  const io::RingFieldCheck field = io::check_ring_field(sweep);
  EXPECT_FALSE(field.usable);
  EXPECT_NE(field.reason.find("do not follow elevation"), std::string::npos) << field.reason;
  const io::ScanClassification scan = io::classify_scan(sweep);
  EXPECT_EQ(scan.structure, io::ScanStructure::Rings) << scan.reason;
  EXPECT_NE(scan.reason.find("ring field ignored"), std::string::npos) << scan.reason;
}

TEST(LidarPathChoice, EitherPathCanBeForced) {
  const LeaningBoard board(40000);
  const LidarCloud sweep = vlp16_sweep();
  auto params = Calibrator::Params::preset("default");
  EXPECT_TRUE(lidar_path(board.cloud, params).ring_free);
  EXPECT_FALSE(lidar_path(sweep, params).ring_free);

  params.lidar_scan = Calibrator::LidarScan::RingFree;
  const LidarPath forced = lidar_path(sweep, params);
  EXPECT_TRUE(forced.ring_free);
  EXPECT_NE(forced.reason.find("as lidar_scan forces"), std::string::npos) << forced.reason;
  const LidarInspection ring_free = inspect_lidar(sweep, board.target, params);
  EXPECT_TRUE(ring_free.ring_free);
  EXPECT_FALSE(ring_free.cloud.has_ring());

  params.lidar_scan = Calibrator::LidarScan::Rings;
  EXPECT_FALSE(lidar_path(board.cloud, params).ring_free);
  const LidarInspection rings = inspect_lidar(board.cloud, board.target, params);
  EXPECT_FALSE(rings.ring_free);
  EXPECT_EQ(rings.cloud.ring.size(), rings.cloud.size());  // recovered from the returns
}

TEST(LidarPathChoice, TheInspectionSaysWhichPathAndWhy) {
  const LeaningBoard board(40000);
  LidarCloud cloud = board.cloud;
  cloud.ring.assign(cloud.size(), 3);
  const auto params = Calibrator::Params::preset("default");
  const LidarInspection in = inspect_lidar(cloud, board.target, params);
  EXPECT_NE(in.path.find("ring-free"), std::string::npos) << in.path;
  EXPECT_NE(in.path.find("ring field ignored"), std::string::npos) << in.path;
  EXPECT_NE(describe(in, params).find("path             ring-free"), std::string::npos);
}

}  // namespace
}  // namespace l2s
