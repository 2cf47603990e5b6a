#pragma once
// YAML building blocks shared by the readers and writers of l2s::io: loading a
// file with errors that name it, the ROS rows/cols/data matrix node, numbers
// written in their shortest exact form, and the transform node that result
// writers embed beside their own keys.

#include <yaml-cpp/yaml.h>
#include <Eigen/Core>
#include <Eigen/Geometry>

#include <string>
#include <vector>

namespace l2s::io::yaml {

/// Parses a YAML file; FileError(path) when it is missing or malformed.
YAML::Node load_file(const std::string& path);

/// True when `node` is a map holding `key`.
bool has_key(const YAML::Node& node, const std::string& key);

/// Reads `map[key]` as a finite number; FileError(path) naming the key otherwise.
double read_double(const YAML::Node& map, const std::string& key, const std::string& path);

/// Reads `map[key]` as an integer > 0; FileError(path) naming the key otherwise.
int read_positive_int(const YAML::Node& map, const std::string& key, const std::string& path);

/// Reads `map[key]` as a string; FileError(path) naming the key otherwise.
std::string read_string(const YAML::Node& map, const std::string& key, const std::string& path);

/// Reads a rows/cols/data matrix node stored under `key`. `rows`/`cols` < 0
/// accept any size (the stored rows/cols are then only checked against data).
Eigen::MatrixXd read_matrix(const YAML::Node& map, const std::string& key, const std::string& path,
                            int rows, int cols);

/// The values of a matrix node's data, for vectors stored as matrices
/// (distortion_coefficients: 1 x N with N = 0, 4, 5, 8, ...).
std::vector<double> read_vector(const YAML::Node& map, const std::string& key,
                                const std::string& path);

/// Shortest text that reads back as exactly `value` (".nan", ".inf" for non-finite).
std::string format_number(double value);

/// Emits `key: {rows, cols, data: [...]}` (data as a flow sequence, row-major)
/// into a block map that the caller has begun.
void emit_matrix(YAML::Emitter& out, const std::string& key, const Eigen::MatrixXd& matrix);

/// Emits a 4x4 transform under `key` (DATASET.md, "Transforms").
void emit_transform(YAML::Emitter& out, const std::string& key, const Eigen::Isometry3d& T);

/// The comment that heads every T_lidar_camera file (DATASET.md), ending in a newline.
std::string transform_header_comment();

/// The emitter's document as file content, ending in a newline.
std::string document_text(const YAML::Emitter& out);

}  // namespace l2s::io::yaml
