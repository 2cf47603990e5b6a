// Transform files (ground_truth.yaml, calibration results).
//
// Rotation check: a rotation whose columns are orthonormal within 1e-9 is kept
// bit for bit (our own files round-trip exactly); one within 1e-3 (printed with
// a few decimals by another tool) is projected onto the nearest rotation (SVD);
// anything further off, or a reflection, is an error rather than a guess.
#include <l2s/io/transform_yaml.hpp>

#include <l2s/error.hpp>

#include "detail/atomic_file.hpp"
#include "io/yaml_helpers.hpp"

#include <Eigen/SVD>
#include <sstream>

namespace l2s::io {
namespace {

constexpr double kExactTolerance = 1e-9;
constexpr double kRepairTolerance = 1e-3;

Eigen::Matrix3d nearest_rotation(const Eigen::Matrix3d& M) {
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(M, Eigen::ComputeFullU | Eigen::ComputeFullV);
  return svd.matrixU() * svd.matrixV().transpose();
}

}  // namespace

Eigen::Isometry3d read_transform(const std::string& path, const std::string& key) {
  const YAML::Node root = yaml::load_file(path);
  if (!root.IsMap()) throw FileError(path, "expected a map holding " + key);
  const Eigen::Matrix4d M = yaml::read_matrix(root, key, path, 4, 4);

  const Eigen::RowVector4d last_row(0.0, 0.0, 0.0, 1.0);
  if ((M.row(3) - last_row).cwiseAbs().maxCoeff() > kExactTolerance)
    throw FileError(path, key + ": last row must be 0 0 0 1");

  Eigen::Matrix3d R = M.topLeftCorner<3, 3>();
  const double error = (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  if (error > kRepairTolerance || R.determinant() < 0.0) {
    std::ostringstream message;
    message << key << ": rotation is not orthonormal (max |R^T R - I| = " << error
            << ", det = " << R.determinant() << ")";
    throw FileError(path, message.str());
  }
  if (error > kExactTolerance) R = nearest_rotation(R);

  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = R;
  T.translation() = M.topRightCorner<3, 1>();
  return T;
}

std::string transform_key(const std::string& path) {
  const YAML::Node root = yaml::load_file(path);
  if (root.IsMap())
    for (const char* key : {"T_lidar_camera", "T_lidar_lidar2"})
      if (yaml::has_key(root, key)) return key;
  throw FileError(path, "holds neither T_lidar_camera nor T_lidar_lidar2");
}

void write_transform(const std::string& path, const Eigen::Isometry3d& T, const std::string& key) {
  YAML::Emitter out;
  out << YAML::BeginMap;
  yaml::emit_transform(out, key, T);
  out << YAML::EndMap;
  // The frame comment describes T_lidar_camera only; other keys get none.
  const std::string header = key == "T_lidar_camera" ? yaml::transform_header_comment() : "";
  detail::write_file_atomically(path, header + yaml::document_text(out));
}

}  // namespace l2s::io
