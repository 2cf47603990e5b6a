// Ring recovery against the known laser index of synthetic sweeps from real
// sensor layouts, with elevation jitter, empty beams, NaN and zero points.
#include <l2s/error.hpp>
#include <l2s/io/ring_recovery.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
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

TEST(RingRecovery, RejectsInvalidParams) {
  LidarCloud cloud;
  RingRecoveryParams params;
  params.min_gap = 0.0;
  EXPECT_THROW(recover_rings(cloud, params), ParamError);
  params = {};
  params.min_points_per_ring = 0;
  EXPECT_THROW(recover_rings(cloud, params), ParamError);
}

}  // namespace
}  // namespace l2s::io
