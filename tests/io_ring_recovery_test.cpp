// Ring recovery against the known laser index of synthetic sweeps from real
// sensor layouts, with elevation jitter, empty beams, NaN and zero points:
// first beams from the sensor origin, then beams from their own origins (the
// vertical offsets and off-axis beams of real calibration tables), at ranges
// down to 0.2 m, where elevations seen from the origin mix the lasers.
#include <l2s/error.hpp>
#include <l2s/io/ring_recovery.hpp>

#include "support/laser_sweep.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <set>

namespace l2s::io {
namespace {

constexpr double kDeg = M_PI / 180.0;

std::vector<double> vlp16() {
  std::vector<double> e;
  for (int k = 0; k < 16; ++k) e.push_back(-15.0 + 2.0 * k);
  return e;
}

std::vector<double> hdl32e() {
  std::vector<double> e;
  for (int k = 0; k < 32; ++k) e.push_back(-30.67 + 4.0 / 3.0 * k);
  return e;
}

std::vector<double> hdl64e() {
  std::vector<double> e;
  for (int k = 31; k >= 0; --k) e.push_back(-8.83 - 0.5 * k);  // lower block
  for (int k = 31; k >= 0; --k) e.push_back(2.0 - k / 3.0);    // upper block
  return e;
}

// VLP-32C: dense around the horizon, sparse towards the ends.
std::vector<double> vlp32c() {
  return {-25,   -15.639, -11.31, -8.843, -7.254, -6.148, -5.333, -4.667, -4,     -3.667, -3.333,
          -3,    -2.667,  -2.333, -2,     -1.667, -1.333, -1,     -0.667, -0.333, 0,      0.333,
          0.667, 1,       1.333,  1.667,  2.333,  3.333,  4.667,  7,      10.333, 15};
}

struct Sweep {
  LidarCloud cloud;
  std::vector<int> truth;  // laser index per point, -1 for invalid points
};

// One sweep of `elevations_deg` (ascending: index = laser id), beams in `silent` without returns.
Sweep simulate(const std::vector<double>& elevations_deg, const std::set<int>& silent,
               double jitter_deg, unsigned seed, int points_per_beam = 400) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> jitter(0.0, jitter_deg);
  std::uniform_real_distribution<double> azimuth(-M_PI, M_PI), range(1.5, 60.0);
  Sweep sweep;
  for (int beam = 0; beam < static_cast<int>(elevations_deg.size()); ++beam) {
    if (silent.count(beam)) continue;
    for (int k = 0; k < points_per_beam; ++k) {
      const double e = (elevations_deg[beam] + jitter(rng)) * kDeg, a = azimuth(rng),
                   r = range(rng);
      sweep.cloud.points.emplace_back(r * std::cos(e) * std::cos(a), r * std::cos(e) * std::sin(a),
                                      r * std::sin(e));
      sweep.truth.push_back(beam);
    }
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (int k = 0; k < 50; ++k) {
    sweep.cloud.points.emplace_back(nan, nan, nan);
    sweep.truth.push_back(-1);
    sweep.cloud.points.emplace_back(0.0, 0.0, 0.0);  // "no return" in some drivers
    sweep.truth.push_back(-1);
  }
  // Drivers emit points in firing order, not by ring: shuffle.
  std::vector<std::size_t> order(sweep.truth.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::shuffle(order.begin(), order.end(), rng);
  Sweep shuffled;
  for (std::size_t i : order) {
    shuffled.cloud.points.push_back(sweep.cloud.points[i]);
    shuffled.truth.push_back(sweep.truth[i]);
  }
  return shuffled;
}

struct Layout {
  const char* name;
  std::vector<double> elevations;
  std::set<int> silent;
};

class RingRecovery : public ::testing::TestWithParam<Layout> {};

TEST_P(RingRecovery, RecoversTheLaserIndexOfEveryPoint) {
  const Layout& layout = GetParam();
  Sweep sweep = simulate(layout.elevations, layout.silent, 0.02, 17);
  const int rings = recover_rings(sweep.cloud);
  ASSERT_EQ(sweep.cloud.ring.size(), sweep.cloud.size());
  const int highest = static_cast<int>(layout.elevations.size()) - 1;
  const int highest_lit = *std::max_element(sweep.truth.begin(), sweep.truth.end());
  EXPECT_EQ(rings, highest_lit + 1) << "beams up to " << highest;
  std::size_t wrong = 0;
  for (std::size_t i = 0; i < sweep.truth.size(); ++i) {
    const int expected = sweep.truth[i] < 0 ? 0 : sweep.truth[i];
    if (sweep.cloud.ring[i] != expected && wrong++ < 5)
      ADD_FAILURE() << "point " << i << ": ring " << sweep.cloud.ring[i] << ", laser " << expected;
  }
  EXPECT_EQ(wrong, 0u);
}

INSTANTIATE_TEST_SUITE_P(
    Sensors, RingRecovery,
    ::testing::Values(Layout{"VLP16", vlp16(), {}},
                      Layout{"VLP16_SilentBeams", vlp16(), {4, 5, 11}},
                      Layout{"HDL32E", hdl32e(), {}},
                      Layout{"HDL32E_SilentBeams", hdl32e(), {2, 9, 20}},
                      Layout{"HDL64E", hdl64e(), {}},
                      // Silent beams on both sides of the block boundary (indices 31 | 32).
                      Layout{"HDL64E_SilentBeams", hdl64e(), {3, 17, 31, 33, 50}},
                      Layout{"HDL64E_SilentBeamsAtBoundary", hdl64e(), {32, 40}}),
    [](const auto& info) { return std::string(info.param.name); });

// Nothing in a sweep tells a silent lowest beam from no beam at all: numbering
// starts at the lowest beam that returned something.
TEST(RingRecovery, StartsAtTheLowestBeamWithReturns) {
  Sweep sweep = simulate(vlp16(), {0}, 0.02, 21);
  EXPECT_EQ(recover_rings(sweep.cloud), 15);
  for (std::size_t i = 0; i < sweep.truth.size(); ++i) {
    if (sweep.truth[i] >= 0) {
      ASSERT_EQ(sweep.cloud.ring[i], sweep.truth[i] - 1) << i;
    }
  }
}

TEST(RingRecovery, NumbersAnUnevenFanConsecutively) {
  Sweep sweep = simulate(vlp32c(), {}, 0.02, 5);
  EXPECT_EQ(recover_rings(sweep.cloud), 32);
  for (std::size_t i = 0; i < sweep.truth.size(); ++i) {
    if (sweep.truth[i] >= 0) {
      ASSERT_EQ(sweep.cloud.ring[i], sweep.truth[i]) << i;
    }
  }
}

TEST(RingRecovery, FoldsStrayPointsIntoTheNearestRing) {
  Sweep sweep = simulate(vlp16(), {}, 0.02, 9);
  // Two points 0.3 deg above beam 7: too few for a ring of their own.
  for (int k = 0; k < 2; ++k)
    sweep.cloud.points.emplace_back(10.0 * std::cos(-0.7 * kDeg), k, 10.0 * std::sin(-0.7 * kDeg));
  EXPECT_EQ(recover_rings(sweep.cloud), 16);
  EXPECT_EQ(sweep.cloud.ring[sweep.cloud.size() - 1], 7);
  EXPECT_EQ(sweep.cloud.ring[sweep.cloud.size() - 2], 7);
}

TEST(RingRecovery, KeepsConsecutiveNumbersWhenAskedNotToInfer) {
  Sweep sweep = simulate(vlp16(), {4}, 0.02, 3);
  RingRecoveryParams params;
  params.infer_missing_beams = false;
  EXPECT_EQ(recover_rings(sweep.cloud, params), 15);
}

TEST(RingRecovery, HandlesCloudsWithoutValidPoints) {
  LidarCloud empty;
  EXPECT_EQ(recover_rings(empty), 0);
  EXPECT_TRUE(empty.ring.empty());
  LidarCloud invalid;
  invalid.points.assign(3, Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN()));
  EXPECT_EQ(recover_rings(invalid), 0);
  EXPECT_EQ(invalid.ring, std::vector<std::uint16_t>(3, 0));
  LidarCloud one;
  one.points.emplace_back(5.0, 0.0, 1.0);
  EXPECT_EQ(recover_rings(one), 1);
}

// The laser of most returns of each ring, and how many returns (of those at
// least `min_distance` out) carry another laser's ring; `oracle`: how many
// would even when each return went to the laser whose true model (table
// elevation and offset) is nearest: noise and the lateral offsets the model
// leaves out move a few returns of densely packed lasers over the middle.
struct RingPurity {
  std::map<int, int> laser_of_ring;  // ring -> laser
  std::size_t mixed = 0, counted = 0, oracle = 0;
};

int nearest_true_laser(const test::LaserTable& table, const Eigen::Vector3d& p) {
  const double d = std::hypot(p.x(), p.y());
  int best = 0;
  double smallest = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < table.lasers.size(); ++k) {
    const double r = std::abs(p.z() / d - std::tan(table.lasers[k].elevation) -
                              test::model_offset(table.lasers[k]) / d);
    if (r < smallest) smallest = r, best = static_cast<int>(k);
  }
  return best;
}

RingPurity purity(const LidarCloud& cloud, const std::vector<int>& truth, double min_distance,
                  const test::LaserTable& table) {
  std::map<int, std::map<int, int>> votes;  // ring -> laser -> returns
  for (std::size_t i = 0; i < truth.size(); ++i)
    if (truth[i] >= 0) ++votes[cloud.ring[i]][truth[i]];
  RingPurity result;
  for (const auto& [ring, lasers] : votes)
    result.laser_of_ring[ring] =
        std::max_element(lasers.begin(), lasers.end(), [](const auto& a, const auto& b) {
          return a.second < b.second;
        })->first;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    const Eigen::Vector3d& p = cloud.points[i];
    if (truth[i] < 0 || std::hypot(p.x(), p.y()) < min_distance) continue;
    ++result.counted;
    result.mixed += result.laser_of_ring[cloud.ring[i]] != truth[i];
    result.oracle += nearest_true_laser(table, p) != truth[i];
  }
  return result;
}

struct OffsetCase {
  const char* name;
  test::LaserTable table;
  test::SweepOptions options;
};

void PrintTo(const OffsetCase& c, std::ostream* out) { *out << c.name; }

class RingRecoveryWithOffsets : public ::testing::TestWithParam<OffsetCase> {};

// One ring per laser, numbered as the sensor numbers its lasers; returns
// beyond 1 m carry their own laser's ring as often as the true laser models
// would give it (nearer, the lines of lasers 0.33 deg apart run into each
// other within the noise).
TEST_P(RingRecoveryWithOffsets, GivesEachLaserExactlyOneRing) {
  const OffsetCase& c = GetParam();
  test::LaserSweep sweep = test::laser_sweep(c.table, c.options);
  const RingRecoveryReport report = recover_ring_structure(sweep.cloud);
  const std::size_t lasers = c.table.lasers.size(), lit = lasers - c.options.silent.size();
  EXPECT_EQ(report.rings, static_cast<int>(lasers)) << report.summary();
  EXPECT_EQ(report.lasers.size(), lit);
  EXPECT_EQ(report.structure, ScanStructure::Rings) << report.summary();
  const RingPurity result = purity(sweep.cloud, sweep.truth, 1.0, c.table);
  for (const auto& [ring, laser] : result.laser_of_ring) EXPECT_EQ(ring, laser);
  EXPECT_LE(result.mixed, result.oracle + result.counted / 1000)
      << result.mixed << " of " << result.counted << ", true models " << result.oracle;
  EXPECT_EQ(test::distinct_rings(sweep.cloud, sweep.truth), lit);
}

test::SweepOptions options(int points_per_laser, double jitter_deg, std::set<int> silent = {},
                           unsigned seed = 17) {
  test::SweepOptions o;
  o.points_per_laser = points_per_laser;
  o.jitter_deg = jitter_deg;
  o.range_sigma = jitter_deg > 0.03 ? 0.03 : 0.01;
  o.silent = std::move(silent);
  o.seed = seed;
  return o;
}

// Ranges log-uniform over 0.2-60 m. Before the laser model, recovery from
// elevations seen from the origin found 12 rings for these VLP-16 sweeps, 15
// for the HDL-32E, 109 for the HDL-64E and 34 for the VLP-32C.
INSTANTIATE_TEST_SUITE_P(
    Sensors, RingRecoveryWithOffsets,
    ::testing::Values(
        OffsetCase{"VLP16", test::vlp16_table(), options(400, 0.02)},
        OffsetCase{"VLP16_FewReturns", test::vlp16_table(), options(20, 0.02)},
        OffsetCase{"VLP16_SilentBeams", test::vlp16_table(), options(400, 0.02, {4, 5, 11})},
        OffsetCase{"HDL32E", test::hdl32e_table(), options(400, 0.02)},
        OffsetCase{"HDL32E_Noisy", test::hdl32e_table(), options(400, 0.05)},
        OffsetCase{"HDL32E_FewReturns", test::hdl32e_table(), options(25, 0.02)},
        OffsetCase{"HDL64E", test::hdl64e_table(), options(400, 0.02)},
        OffsetCase{"HDL64E_SilentBeams", test::hdl64e_table(), options(400, 0.02, {3, 31, 33, 50})},
        OffsetCase{"HDL64E_Noisy", test::hdl64e_table(), options(400, 0.05)},
        OffsetCase{"VLP32C", test::vlp32c_table(), options(400, 0.02)},
        OffsetCase{"VLP32C_Noisy", test::vlp32c_table(), options(400, 0.05)}),
    [](const auto& info) { return std::string(info.param.name); });

// A corridor seen by a lidar on a cart: floor, walls 1.3 m away, a post 0.35 m
// from the sensor. Before the laser model: 24 rings from a VLP-16, 30 from an
// HDL-32E, 8 from an HDL-64E, 27 from a VLP-32C.
class RingRecoveryInCorridor : public ::testing::TestWithParam<test::LaserTable> {};

TEST_P(RingRecoveryInCorridor, GivesEachLaserExactlyOneRing) {
  const test::LaserTable& table = GetParam();
  test::OrganisedSweep sweep = test::corridor_sweep(table, {});
  std::vector<int> truth;
  for (std::size_t i = 0; i < sweep.cloud.size(); ++i)
    truth.push_back(sweep.cloud.points[i].allFinite() ? static_cast<int>(i / sweep.columns) : -1);
  const RingRecoveryReport report = recover_ring_structure(sweep.cloud);
  EXPECT_EQ(report.rings, static_cast<int>(table.lasers.size())) << report.summary();
  EXPECT_FALSE(report.doubtful) << report.summary();
  const RingPurity result = purity(sweep.cloud, truth, 1.0, table);
  for (const auto& [ring, laser] : result.laser_of_ring) EXPECT_EQ(ring, laser);
  EXPECT_LE(result.mixed, result.oracle + result.counted / 1000)
      << result.mixed << " of " << result.counted << ", true models " << result.oracle;
}

INSTANTIATE_TEST_SUITE_P(Sensors, RingRecoveryInCorridor,
                         ::testing::Values(test::vlp16_table(), test::hdl32e_table(),
                                           test::hdl64e_table(), test::vlp32c_table()),
                         [](const auto& info) { return info.param.name; });

// The model's offsets are the lasers' own: h = vertical offset / cos(e) -
// radial * tan(e) (the VLP-16: +-2 cm), and its elevations those of the table.
TEST(RingRecovery, ReportsEachLasersElevationAndOffset) {
  const test::LaserTable table = test::vlp16_table();
  test::LaserSweep sweep = test::laser_sweep(table, options(400, 0.02));
  const RingRecoveryReport report = recover_ring_structure(sweep.cloud);
  ASSERT_EQ(report.lasers.size(), table.lasers.size());
  for (std::size_t k = 0; k < table.lasers.size(); ++k) {
    EXPECT_EQ(report.lasers[k].ring, static_cast<int>(k));
    EXPECT_NEAR(report.lasers[k].elevation, table.lasers[k].elevation, 0.01 * kDeg) << k;
    EXPECT_NEAR(report.lasers[k].offset, test::model_offset(table.lasers[k]), 0.002) << k;
    EXPECT_NEAR(report.lasers[k].rms, 0.02 * kDeg, 0.01 * kDeg) << k;
    EXPECT_EQ(report.lasers[k].points, 400u);
  }
  EXPECT_EQ(report.min_points, 400u);
  EXPECT_EQ(report.median_points, 400.0);
  EXPECT_EQ(report.points, 16u * 400u);
  EXPECT_LT(report.fill, 0.1);
  EXPECT_GT(report.contrast, 20.0);
}

TEST(RingRecovery, RejectsInvalidParams) {
  LidarCloud cloud;
  RingRecoveryParams params;
  params.min_gap = 0.0;
  EXPECT_THROW(recover_rings(cloud, params), ParamError);
  params = {};
  params.min_points_per_ring = 0;
  EXPECT_THROW(recover_rings(cloud, params), ParamError);
  params = {};
  params.max_offset = 0.0;
  EXPECT_THROW(recover_rings(cloud, params), ParamError);
  params = {};
  params.max_fit_points = 10;
  EXPECT_THROW(recover_rings(cloud, params), ParamError);
}

}  // namespace
}  // namespace l2s::io
