// target.yaml (DATASET.md): every key optional, unknown keys ignored so that a
// file may carry notes; the board is validated after reading.
#include <l2s/io/target_yaml.hpp>

#include <l2s/error.hpp>

#include "detail/atomic_file.hpp"
#include "io/yaml_helpers.hpp"

#include <filesystem>

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

}  // namespace

Target read_target(const std::string& path) {
  const YAML::Node root = yaml::load_file(path);
  Target target;
  if (root.IsNull()) return target;  // an empty file means "all defaults"
  if (!root.IsMap()) throw FileError(path, "expected a map of board dimensions");
  for (const Field& field : kFields)
    if (yaml::has_key(root, field.key))
      target.*field.member = yaml::read_double(root, field.key, path);
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
  out << YAML::EndMap;
  detail::write_file_atomically(
      path, "# Calibration board, lengths in metres (DATASET.md).\n" + yaml::document_text(out));
}

}  // namespace l2s::io
