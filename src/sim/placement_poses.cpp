// Board poses spread over the view the lidar and camera share (issue 9): the
// placement search's grid (placement_search.cpp) is cut into slots, one per
// pose, by lateral position and distance, and the search runs in each slot.
// The slot order puts the first poses far apart, so the first P of the spread
// are a spread of their own for every P (the suite's poses experiment takes
// prefixes of one recording).

#include <l2s/sim/multi_pose.hpp>

#include <l2s/error.hpp>

#include <algorithm>
#include <cmath>

namespace l2s::sim {
namespace {

struct Slot {
  double y_min, y_max;  ///< [m] lateral range (body y, left positive)
  double x_min, x_max;  ///< [m] distance range
  int yaw_sign;         ///< +1 / -1: only yaws of that sign, 0: all
};

// Centre; left and near; right and far; left of centre and far; right of
// centre and near. Nearer than 4.4 m: the stereo board detection degrades
// with distance squared, and a pose the camera misses adds nothing.
constexpr Slot kSlots[] = {{-0.2, 0.2, 2.8, 4.0, 0},  {0.4, 1.0, 2.4, 3.4, 1},  {-1.0, -0.4, 3.4, 4.4, -1},
                           {0.1, 0.65, 3.4, 4.4, -1}, {-0.65, -0.1, 2.4, 3.4, 1}};
constexpr double kFarthest = 4.4;  ///< [m] of the fallback band

template <class Keep>
std::vector<double> filtered(const std::vector<double>& values, Keep keep) {
  std::vector<double> out;
  std::copy_if(values.begin(), values.end(), std::back_inserter(out), keep);
  return out;
}

/// The grid within `slot`, its lateral range widened by `widen` [m] and its
/// distances up to `farthest` [m] (0: the slot's own band).
PlacementSearch slot_search(const PlacementSearch& grid, const Slot& slot, double widen, double farthest) {
  PlacementSearch s = grid;
  s.lateral = filtered(grid.lateral, [&](double y) { return y >= slot.y_min - widen && y <= slot.y_max + widen; });
  const double x_min = farthest > 0.0 ? 0.0 : slot.x_min, x_max = farthest > 0.0 ? farthest : slot.x_max;
  s.distances = filtered(grid.distances, [&](double x) { return x >= x_min && x <= x_max; });
  if (slot.yaw_sign != 0) s.yaws = filtered(grid.yaws, [&](double a) { return a * slot.yaw_sign > 0; });
  return s;
}

// When a slot's own band has no passing pose (the shared view of a rig may
// not reach it): any distance up to kFarthest, then farther, then a wider
// lateral range.
struct Attempt {
  double widen, farthest;
};
constexpr Attempt kAttempts[] = {{0.0, 0.0}, {0.0, kFarthest}, {0.0, 9.9}, {0.3, kFarthest}, {0.3, 9.9}};

/// A pose too close to one already drawn adds little: its board centre
/// within 0.3 m of the other's.
bool near_any(const BoardPose& pose, const std::vector<BoardPose>& poses) {
  for (const BoardPose& p : poses)
    if (std::hypot(std::hypot(p.x - pose.x, p.y - pose.y), p.z - pose.z) < 0.3) return true;
  return false;
}

}  // namespace

std::vector<BoardPose> find_pose_spread(const SimulationConfig& config, int count) {
  if (count < 1 || count > 5) throw ParamError("poses", "must be 1..5");
  config.validate();
  const LidarModel model = with_quirks(LidarModel::by_name(config.lidar), config.lidar_quirks);
  PlacementSearch grid = config.placement_search.value_or(PlacementSearch{});
  grid.threads = config.threads;
  std::vector<BoardPose> poses;
  for (int k = 0; k < count; ++k) {
    for (const Attempt& attempt : kAttempts) {
      const PlacementSearch search = slot_search(grid, kSlots[k], attempt.widen, attempt.farthest);
      if (search.lateral.empty() || search.distances.empty() || search.yaws.empty()) continue;
      const PlacementResult found = find_placement(config.target, config.setting, {model}, config.rig, config.layout, search);
      if (found.found && !near_any(found.pose, poses)) {
        poses.push_back(found.pose);
        break;
      }
    }
  }
  return poses;
}

}  // namespace l2s::sim
