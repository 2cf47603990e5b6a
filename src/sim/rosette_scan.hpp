#pragma once
// Directions of a non-repetitive rosette scan (RosetteScan). Each laser is
// bent by two wedge prisms turning in opposite directions; their deflections
// add as two unit phasors, e^{ia} + e^{-ib}, which trace a rosette of passes
// through the centre of the field of view whose orientation advances by an
// irrational share of a turn from pass to pass, so the pattern never repeats
// and coverage grows with integration time (as Livox sensors do).

#include <l2s/sim/lidar_model.hpp>

#include <cstdint>
#include <vector>

namespace l2s::sim::detail {

/// Azimuth and elevation [rad] in the lidar frame of firings `first` ..
/// `first + count - 1`, counted from the sensor's start (frame f starts at
/// f * shots_per_frame). Azimuths of a turning head are not wrapped.
/// Firings go round the lasers: firing i uses laser i % lasers at time i / point_rate.
void rosette_angles(const RosetteScan& scan, std::uint64_t first, int count, std::vector<double>* azimuth,
                    std::vector<double>* elevation);

}  // namespace l2s::sim::detail
