#include "sim/scene_yaml_camera.hpp"

#include <l2s/error.hpp>

#include <set>

namespace l2s::sim::detail {
namespace {

/// Reads one block of a scene file; errors name the file and the dotted key.
class BlockReader {
 public:
  explicit BlockReader(std::string origin) : origin_(std::move(origin)) {}

  [[noreturn]] void fail(const std::string& key, const std::string& problem) const {
    throw FileError(origin_, "key '" + key + "': " + problem);
  }

  void only_keys(const YAML::Node& map, const std::string& where, const std::set<std::string>& allowed) const {
    if (!map.IsMap()) fail(where, "must be a map");
    for (const auto& item : map)
      if (!allowed.count(item.first.as<std::string>())) fail(where + "." + item.first.as<std::string>(), "unknown key");
  }

  template <class T>
  bool read(const YAML::Node& map, const char* key, const std::string& where, T* value) const {
    const YAML::Node node = map[key];
    if (!node) return false;
    try {
      *value = node.as<T>();
    } catch (const YAML::Exception&) {
      fail(where + "." + key, "has the wrong type");
    }
    return true;
  }

  template <int N>
  bool vector(const YAML::Node& map, const char* key, const std::string& where,
              Eigen::Matrix<double, N, 1>* value) const {
    const YAML::Node node = map[key];
    if (!node) return false;
    const std::string name = where + "." + key;
    if (!node.IsSequence() || node.size() != N) fail(name, "must be a list of " + std::to_string(N) + " numbers");
    for (int i = 0; i < N; ++i) {
      try {
        (*value)[i] = node[i].as<double>();
      } catch (const YAML::Exception&) {
        fail(name, "must be a list of " + std::to_string(N) + " numbers");
      }
    }
    return true;
  }

  /// A name turned into an enum by `parse`, whose ParamError becomes a FileError on the key.
  template <class Parse>
  void name(const YAML::Node& map, const char* key, const std::string& where, Parse parse) const {
    std::string text;
    if (!read(map, key, where, &text)) return;
    try {
      parse(text, where + "." + key);
    } catch (const ParamError& e) {
      fail(where + "." + key, e.problem());
    }
  }

 private:
  std::string origin_;
};

void read_distortion(const BlockReader& r, const YAML::Node& node, const std::string& where,
                     LensDistortion* d) {
  r.only_keys(node, where, {"model", "coefficients"});
  r.name(node, "model", where, [&](const std::string& text, const std::string& field) {
    d->model = distortion_model_from_name(text, field);
  });
  std::vector<double> values;
  if (!r.read(node, "coefficients", where, &values)) values.assign(5, 0.0);
  const std::size_t expected = d->model == DistortionModel::Equidistant ? 4 : 5;
  if (d->model != DistortionModel::None && values.size() != expected)
    r.fail(where + ".coefficients", "needs " + std::to_string(expected) + " numbers for " + name_of(d->model));
  d->coefficients.fill(0.0);
  for (std::size_t i = 0; i < values.size() && i < 5; ++i) d->coefficients[i] = values[i];
}

void read_lens(const BlockReader& r, const YAML::Node& node, const std::string& where, CameraLens* lens) {
  r.only_keys(node, where, {"focal_scale", "aspect", "principal_offset", "distortion"});
  r.read(node, "focal_scale", where, &lens->focal_scale);
  r.read(node, "aspect", where, &lens->aspect);
  r.vector<2>(node, "principal_offset", where, &lens->principal_offset);
  if (const YAML::Node d = node["distortion"]) read_distortion(r, d, where + ".distortion", &lens->distortion);
}

void emit_vector(YAML::Emitter& out, const char* key, const Eigen::VectorXd& v) {
  out << YAML::Key << key << YAML::Value << YAML::Flow << YAML::BeginSeq;
  for (Eigen::Index i = 0; i < v.size(); ++i) out << v[i];
  out << YAML::EndSeq;
}

void emit_lens(YAML::Emitter& out, const char* key, const CameraLens& lens) {
  out << YAML::Key << key << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "focal_scale" << YAML::Value << lens.focal_scale;
  out << YAML::Key << "aspect" << YAML::Value << lens.aspect;
  emit_vector(out, "principal_offset", lens.principal_offset);
  out << YAML::Key << "distortion" << YAML::Value << YAML::Flow << YAML::BeginMap;
  out << YAML::Key << "model" << YAML::Value << name_of(lens.distortion.model);
  out << YAML::Key << "coefficients" << YAML::Value << YAML::Flow << YAML::BeginSeq;
  const std::size_t n = lens.distortion.model == DistortionModel::Equidistant ? 4 : 5;
  for (std::size_t i = 0; i < n; ++i) out << lens.distortion.coefficients[i];
  out << YAML::EndSeq << YAML::EndMap << YAML::EndMap;
}

}  // namespace

void read_camera_block(const YAML::Node& camera, const std::string& origin, StereoRig* rig) {
  const BlockReader r(origin);
  const std::string where = "camera";
  r.only_keys(camera, where, {"width", "height", "horizontal_fov", "baseline", "roll", "distortion", "raw_images",
                              "right_rotation", "right_offset", "left", "right"});
  r.read(camera, "width", where, &rig->width);
  r.read(camera, "height", where, &rig->height);
  r.read(camera, "horizontal_fov", where, &rig->horizontal_fov);
  r.read(camera, "baseline", where, &rig->baseline);
  r.read(camera, "roll", where, &rig->roll);
  // A typical real pair first, so that explicit keys below refine it.
  r.name(camera, "distortion", where, [&](const std::string& text, const std::string& field) {
    *rig = rig->with_real_lenses(distortion_model_from_name(text, field));
  });
  r.read(camera, "raw_images", where, &rig->raw_images);
  r.vector<3>(camera, "right_rotation", where, &rig->right_rotation);
  r.vector<3>(camera, "right_offset", where, &rig->right_offset);
  if (const YAML::Node left = camera["left"]) read_lens(r, left, "camera.left", &rig->lenses[0]);
  if (const YAML::Node right = camera["right"]) read_lens(r, right, "camera.right", &rig->lenses[1]);
}

void read_appearance_block(const YAML::Node& node, const std::string& origin, Appearance* look) {
  const BlockReader r(origin);
  const std::string where = "appearance";
  r.only_keys(node, where, {"board_texture", "background", "sky", "brick_length", "brick_height",
                            "joint_width", "to_light", "ambient", "shadows", "exposure", "vignetting",
                            "blur_sigma", "gamma", "colour"});
  r.name(node, "board_texture", where, [&](const std::string& text, const std::string& field) {
    look->board = board_texture_from_name(text, field);
  });
  r.name(node, "background", where, [&](const std::string& text, const std::string& field) {
    look->background = background_from_name(text, field);
  });
  r.name(node, "sky", where, [&](const std::string& text, const std::string& field) {
    look->sky = sky_from_name(text, field);
  });
  r.read(node, "brick_length", where, &look->brick_length);
  r.read(node, "brick_height", where, &look->brick_height);
  r.read(node, "joint_width", where, &look->joint_width);
  if (r.vector<3>(node, "to_light", where, &look->to_light)) {
    if (!(look->to_light.norm() > 1e-9)) r.fail("appearance.to_light", "must not be zero");
    look->to_light.normalize();
  }
  r.read(node, "ambient", where, &look->ambient);
  r.read(node, "shadows", where, &look->shadows);
  r.read(node, "exposure", where, &look->exposure);
  r.read(node, "vignetting", where, &look->vignetting);
  r.read(node, "blur_sigma", where, &look->blur_sigma);
  r.read(node, "gamma", where, &look->gamma);
  r.read(node, "colour", where, &look->colour);
}

void emit_camera_block(YAML::Emitter& out, const StereoRig& rig) {
  out << YAML::Key << "camera" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "width" << YAML::Value << rig.width;
  out << YAML::Key << "height" << YAML::Value << rig.height;
  out << YAML::Key << "horizontal_fov" << YAML::Value << rig.horizontal_fov;
  out << YAML::Key << "baseline" << YAML::Value << rig.baseline;
  if (rig.roll != 0.0) out << YAML::Key << "roll" << YAML::Value << rig.roll;
  if (!rig.ideal() || rig.raw_images) {
    out << YAML::Key << "raw_images" << YAML::Value << rig.raw_images;
    emit_vector(out, "right_rotation", rig.right_rotation);
    emit_vector(out, "right_offset", rig.right_offset);
    emit_lens(out, "left", rig.lenses[0]);
    emit_lens(out, "right", rig.lenses[1]);
  }
  out << YAML::EndMap;
}

void emit_appearance_block(YAML::Emitter& out, const Appearance& look) {
  out << YAML::Key << "appearance" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "board_texture" << YAML::Value << name_of(look.board);
  out << YAML::Key << "background" << YAML::Value << name_of(look.background);
  out << YAML::Key << "sky" << YAML::Value << name_of(look.sky);
  out << YAML::Key << "brick_length" << YAML::Value << look.brick_length;
  out << YAML::Key << "brick_height" << YAML::Value << look.brick_height;
  out << YAML::Key << "joint_width" << YAML::Value << look.joint_width;
  emit_vector(out, "to_light", look.to_light);
  out << YAML::Key << "ambient" << YAML::Value << look.ambient;
  out << YAML::Key << "shadows" << YAML::Value << look.shadows;
  out << YAML::Key << "exposure" << YAML::Value << look.exposure;
  out << YAML::Key << "vignetting" << YAML::Value << look.vignetting;
  out << YAML::Key << "blur_sigma" << YAML::Value << look.blur_sigma;
  out << YAML::Key << "gamma" << YAML::Value << look.gamma;
  out << YAML::Key << "colour" << YAML::Value << look.colour;
  out << YAML::EndMap;
}

}  // namespace l2s::sim::detail
