// Rings from the rows of organised clouds (HEIGHT > 1): rows that are lasers
// (drivers pad missing returns with NaN, some store the top laser first or in
// firing order), and organised clouds whose rows are something else.
#include <l2s/error.hpp>
#include <l2s/io/ring_recovery.hpp>

#include "support/laser_sweep.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <numeric>

namespace l2s::io {
namespace {

// The cloud with its rows in `order` (new row r is old row order[r]).
LidarCloud reorder_rows(const test::OrganisedSweep& sweep, const std::vector<std::size_t>& order) {
  LidarCloud cloud;
  for (std::size_t row : order)
    for (std::size_t c = 0; c < sweep.columns; ++c)
      cloud.points.push_back(sweep.cloud.points[row * sweep.columns + c]);
  return cloud;
}

// Each finite return's ring must be ring_of_old_row[its old row].
void expect_rings(const LidarCloud& cloud, const std::vector<std::size_t>& order,
                  std::size_t columns, const std::vector<int>& ring_of_old_row) {
  std::size_t wrong = 0;
  for (std::size_t i = 0; i < cloud.size(); ++i)
    if (cloud.points[i].allFinite()) wrong += cloud.ring[i] != ring_of_old_row[order[i / columns]];
  EXPECT_EQ(wrong, 0u);
}

std::vector<std::size_t> identity(std::size_t n) {
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  return order;
}

// Drivers pad what a laser did not return: here every return beyond 15 m
// (end walls) and a seventh of the others (dark surfaces) become NaN.
void pad_with_nan(test::OrganisedSweep& sweep) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t i = 0; i < sweep.cloud.size(); ++i)
    if (i % 7 == 3 || sweep.cloud.points[i].norm() > 15.0)
      sweep.cloud.points[i] = Eigen::Vector3d::Constant(nan);
}

class OrganisedRows : public ::testing::TestWithParam<test::LaserTable> {};

// The case: beams 3.4 cm off the axis, returns down to 0.2 m, missing
// returns padded with NaN. Each row is one laser whatever its returns' elevations.
TEST_P(OrganisedRows, RowsOfLasersAreTheRings) {
  test::OrganisedSweep sweep = test::corridor_sweep(GetParam(), {});
  pad_with_nan(sweep);
  ASSERT_TRUE(std::any_of(sweep.cloud.points.begin(), sweep.cloud.points.end(),
                          [](const Eigen::Vector3d& p) { return !p.allFinite(); }));
  const RingRecoveryReport report = rings_from_rows(sweep.cloud, sweep.rows);
  EXPECT_EQ(report.source, RingSource::OrganisedRows) << report.summary();
  EXPECT_EQ(report.rings, static_cast<int>(sweep.rows));
  EXPECT_EQ(report.structure, ScanStructure::Rings);
  EXPECT_TRUE(report.note.empty()) << report.note;
  std::vector<int> ring_of_row(sweep.rows);
  std::iota(ring_of_row.begin(), ring_of_row.end(), 0);
  expect_rings(sweep.cloud, identity(sweep.rows), sweep.columns, ring_of_row);
}

INSTANTIATE_TEST_SUITE_P(Sensors, OrganisedRows,
                         ::testing::Values(test::vlp16_table(), test::hdl64e_table()),
                         [](const auto& info) { return info.param.name; });

TEST(OrganisedRowsOrder, TopRowFirstIsNumberedFromTheBottom) {
  const test::OrganisedSweep sweep = test::corridor_sweep(test::vlp16_table(), {});
  std::vector<std::size_t> order = identity(sweep.rows);
  std::reverse(order.begin(), order.end());
  LidarCloud cloud = reorder_rows(sweep, order);
  const RingRecoveryReport report = rings_from_rows(cloud, sweep.rows);
  EXPECT_EQ(report.source, RingSource::OrganisedRows);
  EXPECT_EQ(report.rings, 16);
  expect_rings(cloud, order, sweep.columns, [] {
    std::vector<int> ring(16);
    std::iota(ring.begin(), ring.end(), 0);
    return ring;
  }());
}

// VLP-16 firing order: -15, 1, -13, 3, ... deg.
TEST(OrganisedRowsOrder, RowsInFiringOrderAreNumberedByElevation) {
  const test::OrganisedSweep sweep = test::corridor_sweep(test::vlp16_table(), {});
  std::vector<std::size_t> order;
  for (std::size_t k = 0; k < 8; ++k) order.insert(order.end(), {k, k + 8});
  LidarCloud cloud = reorder_rows(sweep, order);
  const RingRecoveryReport report = rings_from_rows(cloud, sweep.rows);
  EXPECT_EQ(report.source, RingSource::OrganisedRows);
  expect_rings(cloud, order, sweep.columns, [] {
    std::vector<int> ring(16);
    std::iota(ring.begin(), ring.end(), 0);
    return ring;
  }());
}

// An organised cloud stored column by column: each "row" holds one firing of
// all 16 lasers. Not lasers: the laser model recovers the rings instead.
TEST(OrganisedRowsOrder, RowsThatAreNotLasersFallBackToTheLaserModel) {
  const test::OrganisedSweep sweep = test::corridor_sweep(test::vlp16_table(), {});
  LidarCloud cloud;
  std::vector<int> truth;
  for (std::size_t c = 0; c < sweep.columns; ++c)
    for (std::size_t r = 0; r < sweep.rows; ++r) {
      cloud.points.push_back(sweep.cloud.points[r * sweep.columns + c]);
      truth.push_back(static_cast<int>(r));
    }
  const RingRecoveryReport report = rings_from_rows(cloud, sweep.columns);
  EXPECT_EQ(report.source, RingSource::LaserModel);
  EXPECT_NE(report.note.find("rows of the organised cloud are not lasers"), std::string::npos)
      << report.note;
  EXPECT_EQ(report.rings, 16) << report.summary();
  std::size_t wrong = 0;
  for (std::size_t i = 0; i < cloud.size(); ++i)
    if (cloud.points[i].allFinite() && std::hypot(cloud.points[i].x(), cloud.points[i].y()) > 0.5)
      wrong += cloud.ring[i] != truth[i];
  EXPECT_EQ(wrong, 0u);
}

TEST(OrganisedRowsOrder, HeightMustDivideTheCloud) {
  LidarCloud cloud;
  cloud.points.assign(10, Eigen::Vector3d(1.0, 0.0, 0.0));
  EXPECT_THROW(rings_from_rows(cloud, 3), ParamError);
  EXPECT_THROW(rings_from_rows(cloud, 0), ParamError);
}

}  // namespace
}  // namespace l2s::io
