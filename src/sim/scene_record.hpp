#pragma once
// scene.yaml: what a synthetic dataset was made from (setting, board pose,
// scene layout, lidar quirks and laser table, placement margins). Written beside ground_truth.yaml, which
// keeps exactly the DATASET.md form; the calibrator never reads this file.

#include <l2s/sim/simulation.hpp>

#include <string>

namespace l2s::sim::detail {

void write_scene_record(const std::string& path, const SimulationConfig& config,
                        const BoardPose& pose, const Scene& scene, const LidarModel& lidar,
                        const PlacementReport& placement);

}  // namespace l2s::sim::detail
