// Reading and writing Calibrator::Params as YAML, walking the one field list
// of params_fields.hpp in both directions.

#include <l2s/io/calibrator_yaml.hpp>

#include "calibrator/params_fields.hpp"
#include "detail/atomic_file.hpp"
#include "io/yaml_helpers.hpp"

#include <l2s/error.hpp>

#include <limits>
#include <set>
#include <utility>

namespace l2s::io {
namespace {

template <class Enum>
using Names = std::initializer_list<std::pair<Enum, const char*>>;

// Reads the keys present in one mapping; remembers which were known.
class Reader {
 public:
  Reader(YAML::Node node, std::string path, std::string prefix)
      : node_(std::move(node)), path_(std::move(path)), prefix_(std::move(prefix)) {}

  template <class T>
  void field(const char* name, T& value) {
    const YAML::Node item = take(name);
    if (!item) return;
    try {
      value = parse<T>(item);
    } catch (const YAML::Exception&) {
      throw FileError(path_, "key " + prefix_ + name + ": not a valid " + type_name<T>());
    }
  }

  template <class Enum>
  void choice(const char* name, Enum& value, Names<Enum> names) {
    const YAML::Node item = take(name);
    if (!item) return;
    const std::string text = item.IsScalar() ? item.Scalar() : "";
    std::string options;
    for (const auto& [option, option_name] : names) {
      if (text == option_name) {
        value = option;
        return;
      }
      options += std::string(options.empty() ? "" : ", ") + option_name;
    }
    throw FileError(path_, "key " + prefix_ + name + ": '" + text + "' is not one of " + options);
  }

  template <class Visit>
  void section(const char* name, Visit&& visit) {
    const YAML::Node item = take(name);
    if (!item) return;
    if (!item.IsMap()) throw FileError(path_, "key " + prefix_ + name + ": expected a mapping");
    Reader nested(item, path_, prefix_ + name + ".");
    visit(nested);
    nested.reject_unknown();
  }

  void ignore(const char* name) { known_.insert(name); }

  void reject_unknown() const {
    for (const auto& entry : node_) {
      // A key may itself be a mapping or a list ({}: 1): no field is named so.
      if (!entry.first.IsScalar())
        throw FileError(path_, "a key of " + (prefix_.empty() ? std::string("the file") : prefix_) + " is not a name");
      const std::string key = entry.first.as<std::string>();
      if (!known_.count(key)) throw FileError(path_, "unknown key " + prefix_ + key);
    }
  }

 private:
  YAML::Node take(const char* name) {
    known_.insert(name);
    return node_[name];
  }

  template <class T>
  static T parse(const YAML::Node& item) {
    if constexpr (std::is_same_v<T, Eigen::Vector3d>) {
      if (!item.IsSequence() || item.size() != 3) throw YAML::Exception(YAML::Mark(), "size");
      return {item[0].as<double>(), item[1].as<double>(), item[2].as<double>()};
    } else {
      return item.as<T>();
    }
  }

  template <class T>
  static const char* type_name() {
    if constexpr (std::is_same_v<T, bool>) return "boolean (true/false)";
    if constexpr (std::is_same_v<T, Eigen::Vector3d>) return "list of 3 numbers";
    if constexpr (std::is_integral_v<T>) return "integer";
    return "number";
  }

  YAML::Node node_;
  std::string path_;
  std::string prefix_;
  std::set<std::string> known_;
};

class Writer {
 public:
  explicit Writer(YAML::Emitter& out) : out_(out) {}

  template <class T>
  void field(const char* name, const T& value) {
    out_ << YAML::Key << name << YAML::Value;
    if constexpr (std::is_same_v<T, Eigen::Vector3d>) {
      out_ << YAML::Flow << YAML::BeginSeq;
      for (int i = 0; i < 3; ++i) out_ << yaml::format_number(value[i]);
      out_ << YAML::EndSeq;
    } else if constexpr (std::is_floating_point_v<T>) {
      out_ << yaml::format_number(value);
    } else {
      out_ << value;
    }
  }

  template <class Enum>
  void choice(const char* name, const Enum& value, Names<Enum> names) {
    for (const auto& [option, option_name] : names)
      if (option == value) out_ << YAML::Key << name << YAML::Value << option_name;
  }

  template <class Visit>
  void section(const char* name, Visit&& visit) {
    out_ << YAML::Key << name << YAML::Value << YAML::BeginMap;
    visit(*this);
    out_ << YAML::EndMap;
  }

 private:
  YAML::Emitter& out_;
};

}  // namespace

Calibrator::Params read_calibrator_params(const std::string& path) {
  const YAML::Node root = yaml::load_file(path);
  if (!root.IsMap()) throw FileError(path, "expected a YAML mapping of parameters");
  std::string preset = "default";
  if (root["preset"]) preset = yaml::read_string(root, "preset", path);
  Calibrator::Params params;
  try {
    params = Calibrator::Params::preset(preset);
  } catch (const ParamError& error) {
    throw FileError(path, error.what());
  }
  Reader reader(root, path, "");
  reader.ignore("preset");
  detail::visit(reader, params);
  reader.reject_unknown();
  try {
    params.validate();
  } catch (const ParamError& error) {
    throw FileError(path, error.what());
  }
  return params;
}

void write_calibrator_params(const std::string& path, const Calibrator::Params& params,
                             const std::string& preset_comment) {
  YAML::Emitter out;
  out << YAML::BeginMap;
  Writer writer(out);
  auto copy = params;  // visit() takes non-const references for the reader's sake
  detail::visit(writer, copy);
  out << YAML::EndMap;
  std::string text = "# l2scalib calibrator parameters";
  if (!preset_comment.empty()) text += " (" + preset_comment + ")";
  text += "\n# Load with `l2s calibrate --params FILE`; absent keys keep the preset's values.\n";
  detail::write_file_atomically(path, text + yaml::document_text(out));
}

}  // namespace l2s::io
