#include <l2s/sim/lidar_model.hpp>

#include <l2s/error.hpp>

#include <cmath>

namespace l2s::sim {
namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

/// `count` elevations from `lowest_deg` upwards in steps of `step_deg`.
std::vector<double> evenly_spaced(double lowest_deg, double step_deg, int count) {
  std::vector<double> elevations;
  for (int i = 0; i < count; ++i) elevations.push_back((lowest_deg + i * step_deg) * kDeg);
  return elevations;
}

}  // namespace

int LidarModel::azimuth_count() const {
  return static_cast<int>(std::lround(2.0 * 3.14159265358979323846 / azimuth_step));
}

LidarModel LidarModel::vlp16() {
  LidarModel m;
  m.name = "vlp16";
  m.elevations = evenly_spaced(-15.0, 2.0, 16);
  m.azimuth_step = 0.2 * kDeg;
  m.min_range = 0.5;
  m.max_range = 100.0;
  return m;
}

LidarModel LidarModel::hdl32() {
  LidarModel m;
  m.name = "hdl32";
  // -30.67 .. +10.67 deg: 32 beams 4/3 deg apart.
  m.elevations = evenly_spaced(-30.67, 4.0 / 3.0, 32);
  m.azimuth_step = 0.16 * kDeg;
  m.min_range = 0.5;
  m.max_range = 100.0;
  return m;
}

LidarModel LidarModel::hdl64() {
  LidarModel m;
  m.name = "hdl64";
  // Lower block: -24.33 .. -8.83 deg every 0.5 deg; upper block: -8.33 .. +2.0
  // deg every 1/3 deg. Ring 0 is the lowest beam, so the lower block comes first.
  m.elevations = evenly_spaced(-24.33, 0.5, 32);
  const std::vector<double> upper = evenly_spaced(-8.33, 1.0 / 3.0, 32);
  m.elevations.insert(m.elevations.end(), upper.begin(), upper.end());
  // 0.17 deg nominal; a whole number of firings per turn (2118) keeps sweeps seamless.
  m.azimuth_step = 2.0 * 3.14159265358979323846 / 2118.0;
  m.min_range = 0.9;
  m.max_range = 120.0;
  return m;
}

LidarModel LidarModel::by_name(const std::string& name) {
  if (name == "vlp16") return vlp16();
  if (name == "hdl32") return hdl32();
  if (name == "hdl64") return hdl64();
  throw ParamError("lidar", "unknown model '" + name + "' (expected vlp16, hdl32 or hdl64)");
}

void LidarModel::validate() const {
  if (elevations.empty()) throw ParamError("lidar.elevations", "no beams");
  for (std::size_t i = 1; i < elevations.size(); ++i)
    if (!(elevations[i] > elevations[i - 1]))
      throw ParamError("lidar.elevations", "must be strictly ascending (ring 0 = lowest)");
  if (!(azimuth_step > 1e-5 && azimuth_step < 0.1))
    throw ParamError("lidar.azimuth_step", "must be in (1e-5, 0.1) rad");
  if (!(min_range >= 0.0 && max_range > min_range))
    throw ParamError("lidar.max_range", "must exceed min_range >= 0");
  if (!(range_sigma0 >= 0.0)) throw ParamError("lidar.range_sigma0", "must be >= 0");
}

}  // namespace l2s::sim
