// target.yaml (DATASET.md): every key optional, unknown keys ignored so that a
// file may carry notes; the board is validated after reading.
#include <l2s/io/target_yaml.hpp>

#include <l2s/error.hpp>

#include "detail/atomic_file.hpp"
#include "io/yaml_helpers.hpp"

#include <cmath>
#include <filesystem>
#include <vector>

namespace l2s::io {
namespace {

// One table drives reading and writing, so that both always agree on the keys.
struct Field {
  const char* key;
  double Target::*member;
  const char* comment;
};

constexpr Field kFields[] = {
    {"board_width", &Target::board_width, "outer size of the board (long side horizontal)"},
    {"board_height", &Target::board_height, nullptr},
    {"board_thickness", &Target::board_thickness, nullptr},
    {"hole_radius", &Target::hole_radius, nullptr},
    {"hole_spacing_x", &Target::hole_spacing_x, "distance between hole centres, horizontally"},
    {"hole_spacing_y", &Target::hole_spacing_y, "and vertically"},
};

/// A number of a sequence under `field`; FileError naming the field otherwise.
double number_at(const YAML::Node& node, const std::string& field, const std::string& path) {
  try {
    if (node.IsScalar()) {
      const double value = node.as<double>();
      if (std::isfinite(value)) return value;
    }
  } catch (const YAML::Exception&) {
  }
  throw FileError(path, field + ": expected numbers");
}

std::vector<int> read_ids(const YAML::Node& node, const std::string& path) {
  if (!node.IsSequence()) throw FileError(path, "markers.ids: expected a list of integers");
  std::vector<int> ids;
  for (const YAML::Node& item : node) {
    const double value = number_at(item, "markers.ids", path);
    if (value != std::floor(value) || std::abs(value) > 1e6) throw FileError(path, "markers.ids: expected integers");
    ids.push_back(static_cast<int>(value));
  }
  return ids;
}

std::vector<Eigen::Vector2d> read_centres(const YAML::Node& node, const std::string& path) {
  if (!node.IsSequence()) throw FileError(path, "markers.centres: expected a list of [x, y] pairs");
  std::vector<Eigen::Vector2d> centres;
  for (const YAML::Node& item : node) {
    if (!item.IsSequence() || item.size() != 2) throw FileError(path, "markers.centres: expected [x, y] pairs");
    centres.emplace_back(number_at(item[0], "markers.centres", path), number_at(item[1], "markers.centres", path));
  }
  return centres;
}

/// The `markers:` map (DATASET.md); every key but `dictionary` and `size` is required.
MarkerLayout read_markers(const YAML::Node& node, const std::string& path) {
  if (!node.IsMap()) throw FileError(path, "markers: expected a map (dictionary, size, ids, centres)");
  MarkerLayout layout;
  layout.ids.clear();
  layout.centres.clear();
  if (yaml::has_key(node, "dictionary")) {
    if (!node["dictionary"].IsScalar()) throw FileError(path, "markers.dictionary: expected a name like DICT_6X6_250");
    layout.dictionary = node["dictionary"].Scalar();
  }
  if (yaml::has_key(node, "size")) layout.size = number_at(node["size"], "markers.size", path);
  if (!yaml::has_key(node, "ids")) throw FileError(path, "markers.ids: missing");
  if (!yaml::has_key(node, "centres")) throw FileError(path, "markers.centres: missing");
  layout.ids = read_ids(node["ids"], path);
  layout.centres = read_centres(node["centres"], path);
  return layout;
}

void emit_markers(YAML::Emitter& out, const MarkerLayout& m) {
  out << YAML::Key << "markers" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "dictionary" << YAML::Value << m.dictionary;
  out << YAML::Key << "size" << YAML::Value << yaml::format_number(m.size) << YAML::Comment("side of the black square");
  out << YAML::Key << "ids" << YAML::Value << YAML::Flow << m.ids;
  out << YAML::Key << "centres" << YAML::Value << YAML::Flow << YAML::BeginSeq;
  for (const Eigen::Vector2d& c : m.centres)
    out << YAML::Flow << YAML::BeginSeq << yaml::format_number(c.x()) << yaml::format_number(c.y()) << YAML::EndSeq;
  out << YAML::EndSeq << YAML::Comment("x y in the board frame");
  out << YAML::EndMap;
}

}  // namespace

Target read_target(const std::string& path) {
  const YAML::Node root = yaml::load_file(path);
  Target target;
  if (root.IsNull()) return target;  // an empty file means "all defaults"
  if (!root.IsMap()) throw FileError(path, "expected a map of board dimensions");
  for (const Field& field : kFields)
    if (yaml::has_key(root, field.key))
      target.*field.member = yaml::read_double(root, field.key, path);
  if (yaml::has_key(root, "markers")) target.markers = read_markers(root["markers"], path);
  try {
    target.validate();
  } catch (const ParamError& e) {
    throw FileError(path, e.what());
  }
  return target;
}

Target read_target_or_default(const std::string& path) {
  std::error_code error;
  if (!std::filesystem::exists(path, error)) return Target{};
  return read_target(path);
}

void write_target(const std::string& path, const Target& target) {
  YAML::Emitter out;
  out << YAML::BeginMap;
  for (const Field& field : kFields) {
    out << YAML::Key << field.key << YAML::Value << yaml::format_number(target.*field.member);
    if (field.comment) out << YAML::Comment(field.comment);
  }
  if (target.markers) emit_markers(out, *target.markers);
  out << YAML::EndMap;
  detail::write_file_atomically(
      path, "# Calibration board, lengths in metres (DATASET.md).\n" + yaml::document_text(out));
}

}  // namespace l2s::io
