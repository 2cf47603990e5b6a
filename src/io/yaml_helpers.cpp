#include "io/yaml_helpers.hpp"

#include <l2s/error.hpp>

#include <charconv>
#include <cmath>
#include <filesystem>
#include <limits>

namespace l2s::io::yaml {
namespace {

std::string describe(const YAML::Node& node) {
  if (node.IsScalar()) return "'" + node.Scalar() + "'";
  if (node.IsSequence()) return "a sequence";
  if (node.IsMap()) return "a map";
  return "nothing";
}

const YAML::Node required(const YAML::Node& map, const std::string& key, const std::string& path) {
  if (!map.IsMap()) throw FileError(path, "expected a YAML map at the top level");
  const YAML::Node node = map[key];
  if (!node) throw FileError(path, "missing key " + key);
  return node;
}

bool to_double(const YAML::Node& node, double& value) {
  return node.IsScalar() && YAML::convert<double>::decode(node, value);
}

bool to_integer(const YAML::Node& node, long long& value) {
  return node.IsScalar() && YAML::convert<long long>::decode(node, value);
}

}  // namespace

YAML::Node load_file(const std::string& path) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) throw FileError(path, "missing file");
  try {
    return YAML::LoadFile(path);
  } catch (const YAML::BadFile&) {
    throw FileError(path, "cannot open for reading");
  } catch (const YAML::Exception& e) {
    throw FileError(path, std::string("malformed YAML: ") + e.what());
  }
}

bool has_key(const YAML::Node& node, const std::string& key) { return node.IsMap() && node[key]; }

double read_double(const YAML::Node& map, const std::string& key, const std::string& path) {
  const YAML::Node node = required(map, key, path);
  double value = 0.0;
  if (!to_double(node, value) || !std::isfinite(value))
    throw FileError(path, key + ": expected a number, got " + describe(node));
  return value;
}

int read_positive_int(const YAML::Node& map, const std::string& key, const std::string& path) {
  const YAML::Node node = required(map, key, path);
  long long value = 0;
  if (!to_integer(node, value) || value <= 0 || value > std::numeric_limits<int>::max())
    throw FileError(path, key + ": expected a positive integer, got " + describe(node));
  return static_cast<int>(value);
}

std::string read_string(const YAML::Node& map, const std::string& key, const std::string& path) {
  const YAML::Node node = required(map, key, path);
  if (!node.IsScalar()) throw FileError(path, key + ": expected a string, got " + describe(node));
  return node.Scalar();
}

Eigen::MatrixXd read_matrix(const YAML::Node& map, const std::string& key, const std::string& path,
                            int rows, int cols) {
  const YAML::Node node = required(map, key, path);
  if (!node.IsMap()) throw FileError(path, key + ": expected a map with rows, cols and data");
  const YAML::Node data = node["data"];
  if (!data || !data.IsSequence()) throw FileError(path, key + ": data must be a sequence");
  const long long size = static_cast<long long>(data.size());

  // rows/cols may be absent in hand-written files; data alone then decides.
  long long stored_rows = -1, stored_cols = -1;
  for (const char* name : {"rows", "cols"}) {
    const YAML::Node n = node[name];
    if (!n) continue;
    long long& target = std::string(name) == "rows" ? stored_rows : stored_cols;
    if (!to_integer(n, target) || target < 0)
      throw FileError(path,
                      key + "." + name + ": expected a non-negative integer, got " + describe(n));
  }
  if (rows >= 0 && stored_rows >= 0 && stored_rows != rows)
    throw FileError(path, key + ": expected " + std::to_string(rows) + "x" + std::to_string(cols) +
                              ", file says rows " + std::to_string(stored_rows));
  if (cols >= 0 && stored_cols >= 0 && stored_cols != cols)
    throw FileError(path, key + ": expected " + std::to_string(rows) + "x" + std::to_string(cols) +
                              ", file says cols " + std::to_string(stored_cols));
  long long out_rows = rows >= 0 ? rows : stored_rows;
  long long out_cols = cols >= 0 ? cols : stored_cols;
  if (out_rows < 0 && out_cols < 0) out_rows = 1;
  if (out_rows < 0) out_rows = out_cols > 0 ? size / out_cols : 1;
  if (out_cols < 0) out_cols = out_rows > 0 ? size / out_rows : 0;
  if (out_rows * out_cols != size)
    throw FileError(path, key + ": data has " + std::to_string(size) + " values, expected " +
                              std::to_string(out_rows) + "x" + std::to_string(out_cols));

  Eigen::MatrixXd matrix(out_rows, out_cols);
  for (long long i = 0; i < size; ++i) {
    double value = 0.0;
    if (!to_double(data[i], value) || !std::isfinite(value))
      throw FileError(path, key + ": data[" + std::to_string(i) + "] is not a finite number (" +
                                describe(data[i]) + ")");
    matrix(i / out_cols, i % out_cols) = value;
  }
  return matrix;
}

std::vector<double> read_vector(const YAML::Node& map, const std::string& key,
                                const std::string& path) {
  const Eigen::MatrixXd matrix = read_matrix(map, key, path, -1, -1);
  std::vector<double> values;
  values.reserve(matrix.size());
  for (Eigen::Index r = 0; r < matrix.rows(); ++r)
    for (Eigen::Index c = 0; c < matrix.cols(); ++c) values.push_back(matrix(r, c));
  return values;
}

std::string format_number(double value) {
  if (std::isnan(value)) return ".nan";
  if (std::isinf(value)) return value > 0 ? ".inf" : "-.inf";
  if (value == 0.0) return "0";  // also -0.0, which P = -fx * 0 produces
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  std::string text(buffer, result.ptr);
  // YAML 1.1 readers (PyYAML) take "1e-05" for a string; "1.0e-05" is a float everywhere.
  const auto e = text.find('e');
  if (e != std::string::npos && text.find('.') == std::string::npos) text.insert(e, ".0");
  return text;
}

void emit_matrix(YAML::Emitter& out, const std::string& key, const Eigen::MatrixXd& matrix) {
  out << YAML::Key << key << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "rows" << YAML::Value << static_cast<long long>(matrix.rows());
  out << YAML::Key << "cols" << YAML::Value << static_cast<long long>(matrix.cols());
  out << YAML::Key << "data" << YAML::Value << YAML::Flow << YAML::BeginSeq;
  for (Eigen::Index r = 0; r < matrix.rows(); ++r)
    for (Eigen::Index c = 0; c < matrix.cols(); ++c) out << format_number(matrix(r, c));
  out << YAML::EndSeq << YAML::EndMap;
}

void emit_transform(YAML::Emitter& out, const std::string& key, const Eigen::Isometry3d& T) {
  Eigen::Matrix4d matrix = T.matrix();
  matrix.row(3) << 0.0, 0.0, 0.0, 1.0;  // an Isometry's last row is exact by definition
  emit_matrix(out, key, matrix);
}

std::string transform_header_comment() {
  return "# p_lidar = T_lidar_camera * p_camera, camera = left camera optical frame\n"
         "# (x right, y down, z forward); lidar frame x forward, y left, z up.\n";
}

std::string document_text(const YAML::Emitter& out) { return std::string(out.c_str()) + "\n"; }

}  // namespace l2s::io::yaml
