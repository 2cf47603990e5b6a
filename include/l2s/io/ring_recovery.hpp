#pragma once
// Recovers the laser index of each point from its elevation angle, for sweeps
// stored without a `ring` field.

#include <l2s/export.hpp>
#include <l2s/types.hpp>

namespace l2s::io {

struct L2S_EXPORT RingRecoveryParams {
  /// [rad] a gap between sorted elevations larger than this starts a new ring;
  /// must be below the smallest beam spacing (HDL-64E: 0.33 deg) and above the
  /// elevation jitter of one beam. > 0.
  double min_gap = 0.1 * 3.14159265358979 / 180.0;
  /// rings with fewer points are merged into their nearest neighbour (stray points); >= 1
  int min_points_per_ring = 3;
  /// Where the beam spacing is locally regular, a gap of k spacings between two
  /// rings means k - 1 beams without any return: their indices are skipped so
  /// that ring numbers stay the laser indices of the sensor.
  bool infer_missing_beams = true;

  /// Throws ParamError naming the field when a value is out of range.
  void validate() const;
};

/// Fills cloud.ring (0 = lowest elevation) by clustering the elevations
/// atan2(z, hypot(x, y)) of the valid points. Works for 16/32/64-beam sensors
/// with non-uniform spacing. Points that are not finite or sit at the origin
/// (no return) belong to no cluster and get ring 0. Returns the ring count
/// (highest index + 1, counting skipped beams; 0 when no point is valid).
/// Elevations are taken from the sensor origin, so sensors whose lasers sit far
/// apart vertically (HDL-64E) blur rings at very short range.
L2S_EXPORT int recover_rings(LidarCloud& cloud, const RingRecoveryParams& params = {});

}  // namespace l2s::io
