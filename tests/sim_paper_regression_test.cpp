// The paper's nine settings must not change when the simulator learns real
// sensor quirks: with the quirks off (the default), every placement and sweep
// of Table I is the same as before. The expected checksums were computed with
// the simulator of commit 7cbd45a, before the quirks existed.

#include <l2s/sim/lidar_simulator.hpp>
#include <l2s/sim/placement.hpp>
#include <l2s/sim/ray_caster.hpp>
#include <l2s/sim/settings.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

namespace l2s::sim {
namespace {

/// FNV-1a over quantised values: 1 um for lengths, 1e-3 for intensities, so
/// a last-bit difference in floating point does not flip the checksum while
/// any real change does.
class Checksum {
 public:
  void add(double value, double quantum) {
    const auto q = static_cast<std::int64_t>(std::llround(value / quantum));
    for (int i = 0; i < 8; ++i) {
      hash_ ^= static_cast<std::uint64_t>(q >> (8 * i)) & 0xFFu;
      hash_ *= 0x100000001B3ULL;
    }
  }
  std::uint64_t value() const { return hash_; }

 private:
  std::uint64_t hash_ = 0xCBF29CE484222325ULL;
};

std::uint64_t setting_checksum(int index) {
  const SensorSetting setting = paper_setting(index);
  const std::vector<LidarModel> models{LidarModel::vlp16(), LidarModel::hdl32(), LidarModel::hdl64()};
  const PlacementResult placed = find_placement(Target{}, setting, models);
  Checksum sum;
  const BoardPose& p = placed.pose;
  for (double v : {p.x, p.y, p.z, p.yaw, p.pitch, p.roll}) sum.add(v, 1e-6);
  for (const PlacementReport& report : placed.reports)
    for (int rings : report.rings_per_hole) sum.add(rings, 1.0);
  const RayCaster caster(make_scene(Target{}, placed.pose));
  for (const LidarModel& model : models) {
    LidarSimulator::Params params;
    params.seed = 1000 + static_cast<std::uint64_t>(index);
    const LidarCloud cloud = LidarSimulator(model, params).sweep(caster, setting.T_cambody_lidar(), 3);
    sum.add(static_cast<double>(cloud.size()), 1.0);
    for (std::size_t i = 0; i < cloud.size(); ++i) {
      for (int k = 0; k < 3; ++k) sum.add(cloud.points[i][k], 1e-6);
      sum.add(cloud.intensity[i], 1e-3);
      sum.add(cloud.ring[i], 1.0);
    }
  }
  return sum.value();
}

TEST(PaperSettings, PlacementsAndSweepsAreUnchangedWithQuirksOff) {
  // Checksums of setting 1..9 (placement, reports, one sweep of each model).
  const std::uint64_t expected[9] = {
      0x0296B4CA3AB7844DULL, 0xE94612BB9EFC042FULL, 0xCD6D5900879F748CULL,
      0x56EAE9D6CABFB1E3ULL, 0x4B84D7BD232F5A73ULL, 0x23D7F5A1AA11767DULL,
      0xCE4B60AE1C59CF14ULL, 0x206703DCDBB4E0DEULL, 0xBC3BFE486970D248ULL};
  for (int s = 1; s <= 9; ++s) {
    const std::uint64_t actual = setting_checksum(s);
    EXPECT_EQ(actual, expected[s - 1]) << "setting " << s << ": now 0x" << std::hex << actual;
  }
}

}  // namespace
}  // namespace l2s::sim
