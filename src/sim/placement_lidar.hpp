#pragma once
// The lidar side of the placement check (placement.hpp): rings across each
// hole for a spinning lidar, returns through and around each hole within the
// accumulation time for a ring-free one. Both add their figures and readable
// failures to the report.

#include <l2s/sim/lidar_model.hpp>
#include <l2s/sim/placement.hpp>
#include <l2s/sim/ray_caster.hpp>

#include <Eigen/Geometry>

namespace l2s::sim::detail {

extern const char* const kHoleNames[4];

/// Rings crossing each hole, for the worst azimuth offset of the sweep.
void check_lidar_rings(const RayCaster& caster, const LidarModel& lidar, const Eigen::Isometry3d& T_cambody_lidar,
                       const PlacementRequirements& req, PlacementReport* report);

/// Returns of a rosette lidar through and around each hole in req.accumulation_time.
void check_lidar_rosette(const RayCaster& caster, const LidarModel& lidar, const Eigen::Isometry3d& T_cambody_lidar,
                         const PlacementRequirements& req, PlacementReport* report);

}  // namespace l2s::sim::detail
