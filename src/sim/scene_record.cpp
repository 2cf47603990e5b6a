#include "sim/scene_record.hpp"

#include "detail/atomic_file.hpp"
#include "sim/scene_yaml_camera.hpp"

#include <yaml-cpp/yaml.h>

namespace l2s::sim::detail {
namespace {

void emit_matrix(YAML::Emitter& out, const char* key, const Eigen::Isometry3d& T) {
  out << YAML::Key << key << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "rows" << YAML::Value << 4 << YAML::Key << "cols" << YAML::Value << 4;
  out << YAML::Key << "data" << YAML::Value << YAML::Flow << YAML::BeginSeq;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) out << T.matrix()(r, c);
  out << YAML::EndSeq << YAML::EndMap;
}

/// The quirks as the scene file spells them, and the unit's laser table: per
/// ring [elevation, azimuth] corrections [rad] and [vertical, horizontal]
/// beam origin offsets [m] (LidarModel::LaserCorrection).
void emit_quirks(YAML::Emitter& out, const LidarQuirks& quirks, const LidarModel& lidar) {
  out << YAML::Key << "lidar_quirks" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "laser_table" << YAML::Value << quirks.laser_table;
  out << YAML::Key << "beam_footprint" << YAML::Value << quirks.beam_footprint;
  out << YAML::Key << "return_mode" << YAML::Value << return_mode_name(quirks.return_mode);
  out << YAML::Key << "table_seed" << YAML::Value << quirks.table_seed;
  out << YAML::EndMap;
  if (lidar.corrections.empty()) return;
  out << YAML::Key << "laser_table" << YAML::Value << YAML::BeginSeq;
  for (const LidarModel::LaserCorrection& c : lidar.corrections)
    out << YAML::Flow << YAML::BeginSeq << c.elevation << c.azimuth << c.vertical_offset << c.horizontal_offset
        << YAML::EndSeq;
  out << YAML::EndSeq;
}

}  // namespace

void write_scene_record(const std::string& path, const SimulationConfig& config,
                        const BoardPose& pose, const Scene& scene, const LidarModel& lidar,
                        const PlacementReport& placement) {
  YAML::Emitter out;
  out.SetDoublePrecision(10);
  out << YAML::Comment("How this synthetic dataset was made (l2scalib simulator). Frames: camera "
                       "body = x forward, y left, z up at the left camera.");
  out << YAML::BeginMap;
  out << YAML::Key << "setting" << YAML::Value << config.setting_index;
  out << YAML::Key << "sensor_pose" << YAML::Value << YAML::Flow << YAML::BeginMap
      << YAML::Key << "tx" << YAML::Value << config.setting.tx << YAML::Key << "ty" << YAML::Value
      << config.setting.ty << YAML::Key << "tz" << YAML::Value << config.setting.tz << YAML::Key
      << "yaw" << YAML::Value << config.setting.yaw << YAML::Key << "pitch" << YAML::Value
      << config.setting.pitch << YAML::Key << "roll" << YAML::Value << config.setting.roll
      << YAML::EndMap;
  out << YAML::Key << "lidar" << YAML::Value << config.lidar;
  out << YAML::Key << "frames" << YAML::Value << config.frames;
  out << YAML::Key << "noise_factor" << YAML::Value << config.noise_factor;
  out << YAML::Key << "seed" << YAML::Value << config.seed;
  out << YAML::Key << "board_pose" << YAML::Value << YAML::Flow << YAML::BeginMap << YAML::Key
      << "x" << YAML::Value << pose.x << YAML::Key << "y" << YAML::Value << pose.y << YAML::Key
      << "z" << YAML::Value << pose.z << YAML::Key << "yaw" << YAML::Value << pose.yaw << YAML::Key
      << "pitch" << YAML::Value << pose.pitch << YAML::Key << "roll" << YAML::Value << pose.roll
      << YAML::EndMap;
  // --- Camera side (scene_yaml_camera.hpp): rig, image kind, look ---
  emit_camera_block(out, config.rig);
  out << YAML::Key << "images" << YAML::Value
      << (config.rig.images() == ImageKind::Raw ? "raw" : "rectified");
  emit_appearance_block(out, config.appearance);
  out << YAML::Key << "scene" << YAML::Value << YAML::Flow << YAML::BeginMap << YAML::Key
      << "camera_height" << YAML::Value << config.layout.camera_height << YAML::Key << "wall_gap"
      << YAML::Value << config.layout.wall_gap << YAML::Key << "wall_half_width" << YAML::Value
      << config.layout.wall_half_width << YAML::Key << "wall_top" << YAML::Value
      << config.layout.wall_top << YAML::Key << "clutter_boxes" << YAML::Value
      << scene.clutter.size() << YAML::Key << "board_stand" << YAML::Value << config.layout.board_stand
      << YAML::Key << "side_wall_distance" << YAML::Value << config.layout.side_wall_distance << YAML::Key
      << "near_clutter" << YAML::Value << config.layout.near_clutter << YAML::Key << "pillar" << YAML::Value
      << config.layout.pillar << YAML::EndMap;
  emit_quirks(out, config.lidar_quirks, lidar);
  emit_matrix(out, "T_cambody_lidar", config.setting.T_cambody_lidar());
  emit_matrix(out, "T_cambody_board", scene.T_cambody_board);
  emit_matrix(out, "T_lidar_camera", config.T_lidar_camera());  // the dataset's camera frame
  out << YAML::Key << "placement" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "ok" << YAML::Value << placement.ok;
  out << YAML::Key << "image_margin_px" << YAML::Value << placement.image_margin;
  out << YAML::Key << "rings_per_hole" << YAML::Value << YAML::Flow << YAML::BeginSeq
      << placement.rings_per_hole[0] << placement.rings_per_hole[1] << placement.rings_per_hole[2]
      << placement.rings_per_hole[3] << YAML::EndSeq;
  if (placement.ring_free) {
    out << YAML::Key << "returns_through_hole" << YAML::Value << YAML::Flow << YAML::BeginSeq;
    for (int n : placement.returns_through_hole) out << n;
    out << YAML::EndSeq << YAML::Key << "returns_around_hole" << YAML::Value << YAML::Flow << YAML::BeginSeq;
    for (int n : placement.returns_around_hole) out << n;
    out << YAML::EndSeq << YAML::Key << "rim_in_view" << YAML::Value << YAML::Flow << YAML::BeginSeq;
    for (double share : placement.rim_in_view) out << share;
    out << YAML::EndSeq;
  }
  out << YAML::Key << "failures" << YAML::Value << YAML::BeginSeq;
  for (const std::string& f : placement.failures) out << f;
  out << YAML::EndSeq << YAML::EndMap;
  out << YAML::EndMap;
  l2s::detail::write_file_atomically(path, std::string(out.c_str()) + "\n");
}

}  // namespace l2s::sim::detail
