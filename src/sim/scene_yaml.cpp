// Scene files (scene_yaml.hpp): a SimulationConfig in YAML. Unknown keys are
// errors, so a typo never silently falls back to a default.

#include <l2s/sim/scene_yaml.hpp>

#include <l2s/error.hpp>
#include <l2s/sim/settings.hpp>

#include "sim/scene_yaml_camera.hpp"

#include <yaml-cpp/yaml.h>

#include <fstream>
#include <set>
#include <sstream>

namespace l2s::sim {
namespace {

class Reader {
 public:
  explicit Reader(std::string origin) : origin_(std::move(origin)) {}

  [[noreturn]] void fail(const std::string& key, const std::string& problem) const {
    throw FileError(origin_, "key '" + key + "': " + problem);
  }

  void only_keys(const YAML::Node& map, const std::string& where, const std::set<std::string>& allowed) const {
    if (!map.IsMap()) fail(where, "must be a map");
    for (const auto& item : map) {
      const std::string key = item.first.as<std::string>();
      if (!allowed.count(key)) fail(where.empty() ? key : where + "." + key, "unknown key");
    }
  }

  template <class T>
  void read(const YAML::Node& map, const char* key, const std::string& where, T* value) const {
    const YAML::Node node = map[key];
    if (!node) return;
    try {
      *value = node.as<T>();
    } catch (const YAML::Exception&) {
      fail(where.empty() ? key : where + "." + key, "has the wrong type");
    }
  }

  Eigen::Vector3d vector3(const YAML::Node& node, const std::string& key) const {
    if (!node.IsSequence() || node.size() != 3) fail(key, "must be a list of 3 numbers");
    Eigen::Vector3d v;
    for (int i = 0; i < 3; ++i) {
      try {
        v[i] = node[i].as<double>();
      } catch (const YAML::Exception&) {
        fail(key, "must be a list of 3 numbers");
      }
    }
    return v;
  }

 private:
  std::string origin_;
};

/// The `scene` map: the world around the board and the elements of real recordings.
void read_scene(const Reader& r, const YAML::Node& scene, SceneLayout* out) {
  SceneLayout& layout = *out;
  r.only_keys(scene, "scene", {"camera_height", "wall_gap", "wall_half_width", "wall_top", "default_clutter",
                               "clutter", "board_stand", "side_wall_distance", "near_clutter", "pillar"});
  r.read(scene, "camera_height", "scene", &layout.camera_height);
  r.read(scene, "wall_gap", "scene", &layout.wall_gap);
  r.read(scene, "wall_half_width", "scene", &layout.wall_half_width);
  r.read(scene, "wall_top", "scene", &layout.wall_top);
  r.read(scene, "default_clutter", "scene", &layout.default_clutter);
  r.read(scene, "board_stand", "scene", &layout.board_stand);
  r.read(scene, "side_wall_distance", "scene", &layout.side_wall_distance);
  r.read(scene, "near_clutter", "scene", &layout.near_clutter);
  r.read(scene, "pillar", "scene", &layout.pillar);
  if (const YAML::Node boxes = scene["clutter"]) {
    if (!boxes.IsSequence()) r.fail("scene.clutter", "must be a list of boxes");
    for (std::size_t i = 0; i < boxes.size(); ++i) {
      const std::string where = "scene.clutter[" + std::to_string(i) + "]";
      r.only_keys(boxes[i], where, {"center", "size", "yaw"});
      if (!boxes[i]["center"] || !boxes[i]["size"]) r.fail(where, "needs center and size");
      double yaw = 0.0;
      r.read(boxes[i], "yaw", where, &yaw);
      Box box;
      box.T_cambody_box.linear() = rotation_zyx(yaw, 0.0, 0.0);
      box.T_cambody_box.translation() = r.vector3(boxes[i]["center"], where + ".center");
      box.half_size = 0.5 * r.vector3(boxes[i]["size"], where + ".size");
      layout.extra_clutter.push_back(box);
    }
  }
}

/// `lidar_quirks: true|false` (all or none), or a map of the single quirks.
void read_quirks(const Reader& r, const YAML::Node& node, LidarQuirks* quirks) {
  if (node.IsScalar()) {
    bool on = false;
    try {
      on = node.as<bool>();
    } catch (const YAML::Exception&) {
      r.fail("lidar_quirks", "must be true, false or a map");
    }
    *quirks = on ? LidarQuirks::all(quirks->table_seed) : LidarQuirks{};
    return;
  }
  r.only_keys(node, "lidar_quirks", {"laser_table", "beam_footprint", "return_mode", "table_seed"});
  r.read(node, "laser_table", "lidar_quirks", &quirks->laser_table);
  r.read(node, "beam_footprint", "lidar_quirks", &quirks->beam_footprint);
  r.read(node, "table_seed", "lidar_quirks", &quirks->table_seed);
  std::string mode = return_mode_name(quirks->return_mode);
  r.read(node, "return_mode", "lidar_quirks", &mode);
  try {
    quirks->return_mode = return_mode_from_name(mode, "lidar_quirks.return_mode");
  } catch (const ParamError& e) {
    r.fail("lidar_quirks.return_mode", e.problem());
  }
}

/// `setting: 1..9` (a Table I row) or a custom `sensor_pose`, not both.
void read_sensor_pose(const Reader& r, const YAML::Node& root, SimulationConfig* config) {
  if (root["setting"] && root["sensor_pose"]) r.fail("sensor_pose", "give either setting or sensor_pose");
  if (root["setting"]) {
    int index = 0;
    r.read(root, "setting", "", &index);
    if (index < 1 || index > 9) r.fail("setting", "must be 1..9 (Table I)");
    config->setting_index = index;
    config->setting = paper_setting(index);
  }
  if (const YAML::Node pose = root["sensor_pose"]) {
    r.only_keys(pose, "sensor_pose", {"tx", "ty", "tz", "yaw", "pitch", "roll"});
    config->setting_index = 0;
    config->setting = SensorSetting{};
    r.read(pose, "tx", "sensor_pose", &config->setting.tx);
    r.read(pose, "ty", "sensor_pose", &config->setting.ty);
    r.read(pose, "tz", "sensor_pose", &config->setting.tz);
    r.read(pose, "yaw", "sensor_pose", &config->setting.yaw);
    r.read(pose, "pitch", "sensor_pose", &config->setting.pitch);
    r.read(pose, "roll", "sensor_pose", &config->setting.roll);
  }
}

/// `target: NAME` (a Target preset) or a map of its dimensions.
void read_target(const Reader& r, const YAML::Node& target, Target* out) {
  if (target.IsScalar()) {
    try {
      *out = Target::preset(target.as<std::string>());
    } catch (const ParamError& e) {
      r.fail("target", e.what());
    }
    return;
  }
  r.only_keys(target, "target", {"board_width", "board_height", "board_thickness", "hole_radius",
                                 "hole_spacing_x", "hole_spacing_y"});
  r.read(target, "board_width", "target", &out->board_width);
  r.read(target, "board_height", "target", &out->board_height);
  r.read(target, "board_thickness", "target", &out->board_thickness);
  r.read(target, "hole_radius", "target", &out->hole_radius);
  r.read(target, "hole_spacing_x", "target", &out->hole_spacing_x);
  r.read(target, "hole_spacing_y", "target", &out->hole_spacing_y);
}

/// The `board_pose` map (otherwise the board is placed automatically).
BoardPose read_board_pose(const Reader& r, const YAML::Node& pose) {
  r.only_keys(pose, "board_pose", {"x", "y", "z", "yaw", "pitch", "roll"});
  BoardPose board;
  r.read(pose, "x", "board_pose", &board.x);
  r.read(pose, "y", "board_pose", &board.y);
  r.read(pose, "z", "board_pose", &board.z);
  r.read(pose, "yaw", "board_pose", &board.yaw);
  r.read(pose, "pitch", "board_pose", &board.pitch);
  r.read(pose, "roll", "board_pose", &board.roll);
  return board;
}

}  // namespace

SimulationConfig parse_simulation_config(const std::string& yaml_text, const std::string& origin) {
  YAML::Node root;
  try {
    root = YAML::Load(yaml_text);
  } catch (const YAML::Exception& e) {
    throw FileError(origin, std::string("malformed YAML: ") + e.what());
  }
  SimulationConfig config;
  if (!root || root.IsNull()) return config;
  const Reader r(origin);
  r.only_keys(root, "", {"setting", "sensor_pose", "lidar", "frames", "noise_factor", "seed", "target",
                         "board_pose", "camera", "appearance", "scene", "strict_placement", "threads",
                         "lidar_quirks"});

  read_sensor_pose(r, root, &config);
  r.read(root, "lidar", "", &config.lidar);
  r.read(root, "frames", "", &config.frames);
  r.read(root, "noise_factor", "", &config.noise_factor);
  r.read(root, "seed", "", &config.seed);
  r.read(root, "strict_placement", "", &config.strict_placement);
  r.read(root, "threads", "", &config.threads);
  if (const YAML::Node target = root["target"]) read_target(r, target, &config.target);
  if (const YAML::Node pose = root["board_pose"]) config.board_pose = read_board_pose(r, pose);
  // --- Camera side (scene_yaml_camera.hpp): the rig and the scene's look ---
  if (const YAML::Node camera = root["camera"]) detail::read_camera_block(camera, origin, &config.rig);
  if (const YAML::Node look = root["appearance"]) detail::read_appearance_block(look, origin, &config.appearance);
  // --- Scene geometry and the lidar's quirks ---
  if (const YAML::Node scene = root["scene"]) read_scene(r, scene, &config.layout);
  if (const YAML::Node quirks = root["lidar_quirks"]) read_quirks(r, quirks, &config.lidar_quirks);
  try {
    config.validate();
    config.layout.validate();
  } catch (const ParamError& e) {
    throw FileError(origin, e.what());
  }
  return config;
}

SimulationConfig load_simulation_config(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw FileError(path, "cannot open the scene file");
  std::ostringstream text;
  text << in.rdbuf();
  return parse_simulation_config(text.str(), path);
}

}  // namespace l2s::sim
