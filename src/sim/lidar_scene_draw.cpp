// The lidar side of a randomised scene. Ranges: vehicle mountings within
// about 1 m of the camera and +-0.7 rad yaw, +-0.3 rad pitch and roll; boards
// at 1.5 m up to where the model still puts enough samples on a 0.12 m hole
// (two 2 deg VLP-16 rings per hole up to about 3.4 m).

#include <l2s/sim/lidar_scene_draw.hpp>

#include <algorithm>
#include <cmath>

namespace l2s::sim {
namespace {

/// Uniform in [lo, hi) from the generator's raw bits (53 of them).
double uniform(std::mt19937_64& rng, double lo, double hi) {
  return lo + (hi - lo) * static_cast<double>(rng() >> 11) * (1.0 / 9007199254740992.0);
}

bool chance(std::mt19937_64& rng, double p) { return uniform(rng, 0.0, 1.0) < p; }

/// [m] how far a board may stand for this model to resolve its holes.
double reach(const std::string& lidar) {
  if (lidar == "vlp16") return 3.5;
  if (lidar == "hdl32") return 4.5;
  if (lidar == "mid360") return 5.0;
  return 6.0;
}

SensorSetting draw_mounting(std::mt19937_64& rng) {
  SensorSetting pose;
  // A point in the 1 m ball around the camera, not lower than 0.9 m below it
  // (the low boxes of the scene stay below every sensor).
  do {
    pose.tx = uniform(rng, -1.0, 1.0);
    pose.ty = uniform(rng, -1.0, 1.0);
    pose.tz = uniform(rng, -0.9, 1.0);
  } while (pose.tx * pose.tx + pose.ty * pose.ty + pose.tz * pose.tz > 1.0);
  pose.yaw = uniform(rng, -0.7, 0.7);
  pose.pitch = uniform(rng, -0.3, 0.3);
  pose.roll = uniform(rng, -0.3, 0.3);
  return pose;
}

SceneLayout draw_layout(std::mt19937_64& rng, const SensorSetting& lidar_pose) {
  SceneLayout layout;
  layout.board_stand = chance(rng, 0.7);
  // Side walls keep half a metre to the lidar.
  if (chance(rng, 0.5)) layout.side_wall_distance = uniform(rng, std::max(1.0, std::abs(lidar_pose.ty) + 0.5), 3.0);
  layout.near_clutter = static_cast<int>(uniform(rng, 0.0, 4.0));
  layout.pillar = chance(rng, 0.3);
  return layout;
}

}  // namespace

PlacementSearch LidarSceneDraw::placement_search() const {
  PlacementSearch search;
  search.distances = {board_distance};
  search.yaws = {board_yaw};
  search.pitches = {board_pitch};
  search.roll = board_roll;
  return search;
}

void LidarSceneDraw::apply_to(SimulationConfig* config) const {
  config->lidar = lidar;
  config->lidar_quirks = quirks;
  config->setting_index = 0;
  config->setting = lidar_pose;
  config->layout = layout;
  config->board_pose.reset();
  config->placement_search = placement_search();
}

LidarSceneDraw draw_lidar_scene(std::mt19937_64& rng) {
  static const char* const kModels[5] = {"vlp16", "hdl32", "hdl64", "mid360", "avia"};
  LidarSceneDraw draw;
  draw.lidar = kModels[std::min(4, static_cast<int>(uniform(rng, 0.0, 5.0)))];
  draw.quirks = LidarQuirks::all(rng());
  const double mode = uniform(rng, 0.0, 1.0);
  draw.quirks.return_mode = mode < 0.7 ? ReturnMode::Strongest : mode < 0.9 ? ReturnMode::Last : ReturnMode::First;
  draw.lidar_pose = draw_mounting(rng);
  draw.layout = draw_layout(rng, draw.lidar_pose);
  draw.reach = reach(draw.lidar);
  draw.board_distance = uniform(rng, 1.5, draw.reach);
  draw.board_yaw = (chance(rng, 0.5) ? 1.0 : -1.0) * uniform(rng, 0.1, 0.5);
  draw.board_pitch = uniform(rng, -0.1, 0.1);
  draw.board_roll = uniform(rng, -0.1, 0.1);
  return draw;
}

}  // namespace l2s::sim
