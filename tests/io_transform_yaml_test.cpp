// Transform files: exact round trips, the DATASET.md layout, rotation checks.
#include <l2s/error.hpp>
#include <l2s/io/transform_yaml.hpp>

#include "io/yaml_helpers.hpp"
#include "io_test_helpers.hpp"
#include "support/test_data.hpp"

#include <gtest/gtest.h>

namespace l2s::io {
namespace {

Eigen::Isometry3d some_pose() {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = (Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(-0.2, Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(1.1, Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  T.translation() << 0.1234567890123, -0.5, 1e-5;
  return T;
}

std::string matrix_file(const std::string& data) {
  return "T_lidar_camera:\n  rows: 4\n  cols: 4\n  data: [" + data + "]\n";
}

TEST(TransformYaml, RoundTripsBitExactly) {
  test::TempDir dir;
  const Eigen::Isometry3d T = some_pose();
  write_transform(dir.file("gt.yaml"), T);
  const Eigen::Isometry3d back = read_transform(dir.file("gt.yaml"));
  EXPECT_EQ(back.matrix(), T.matrix());
}

TEST(TransformYaml, WritesTheDatasetMdLayout) {
  test::TempDir dir;
  write_transform(dir.file("gt.yaml"), Eigen::Isometry3d::Identity());
  EXPECT_EQ(test::read_bytes(dir.file("gt.yaml")),
            "# p_lidar = T_lidar_camera * p_camera, camera = left camera optical frame\n"
            "# (x right, y down, z forward); lidar frame x forward, y left, z up.\n"
            "T_lidar_camera:\n  rows: 4\n  cols: 4\n"
            "  data: [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]\n");
}

TEST(TransformYaml, ReadsOtherKeysAndFilesWithMoreKeys) {
  test::TempDir dir;
  // What a result writer does: the transform node beside its own keys.
  YAML::Emitter out;
  out << YAML::BeginMap << YAML::Key << "frames_used" << YAML::Value << 7;
  yaml::emit_transform(out, "T_lidar_camera", some_pose());
  yaml::emit_transform(out, "T_other", Eigen::Isometry3d::Identity());
  out << YAML::EndMap;
  test::write_text(dir.file("result.yaml"),
                   yaml::transform_header_comment() + yaml::document_text(out));
  EXPECT_EQ(read_transform(dir.file("result.yaml")).matrix(), some_pose().matrix());
  EXPECT_EQ(read_transform(dir.file("result.yaml"), "T_other").matrix(),
            Eigen::Matrix4d::Identity());
  EXPECT_FILE_ERROR(read_transform(dir.file("result.yaml"), "T_missing"), dir.file("result.yaml"),
                    "missing key T_missing");
}

TEST(TransformYaml, RepairsRotationsRoundedToFewDecimals) {
  test::TempDir dir;
  // Rz(30 deg) printed with 6 decimals: orthonormal only to ~1e-6.
  test::write_text(
      dir.file("t.yaml"),
      matrix_file("0.866025, -0.5, 0, 1,  0.5, 0.866025, 0, 2,  0, 0, 1, 3,  0, 0, 0, 1"));
  const Eigen::Isometry3d T = read_transform(dir.file("t.yaml"));
  const Eigen::Matrix3d R = T.rotation();
  EXPECT_LT((R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff(), 1e-14);
  EXPECT_NEAR(R(0, 0), std::cos(M_PI / 6), 1e-6);
  EXPECT_EQ(T.translation(), Eigen::Vector3d(1, 2, 3));
}

TEST(TransformYaml, BadMatricesAreFileErrorsNamingTheFile) {
  test::TempDir dir;
  const std::string path = dir.file("t.yaml");
  const auto expect_error = [&](const std::string& text, const std::string& words) {
    test::write_text(path, text);
    EXPECT_FILE_ERROR(read_transform(path), path, words);
  };
  expect_error(matrix_file("1, 0, 0, 0,  0, 1, 0, 0,  0, 0, 1, 0,  0, 0, 1, 1"), "last row");
  expect_error(matrix_file("1, 0, 0, 0,  0, 1.1, 0, 0,  0, 0, 1, 0,  0, 0, 0, 1"), "orthonormal");
  expect_error(matrix_file("1, 0, 0, 0,  0, -1, 0, 0,  0, 0, 1, 0,  0, 0, 0, 1"), "orthonormal");
  expect_error(matrix_file("1, 0, 0, 0,  0, 1, 0, 0,  0, 0, 1, 0"), "data has 12 values");
  expect_error("T_lidar_camera:\n  rows: 3\n  cols: 3\n  data: [1, 0, 0, 0, 1, 0, 0, 0, 1]\n",
               "expected 4x4");
  expect_error(matrix_file("1, 0, 0, x,  0, 1, 0, 0,  0, 0, 1, 0,  0, 0, 0, 1"), "data[3]");
  expect_error("T_lidar_camera: [1, 0]\n", "rows, cols and data");
  expect_error("T_lidar_camera:\n  rows: 4\n cols", "malformed YAML");
  expect_error("other: 1\n", "missing key T_lidar_camera");
  EXPECT_FILE_ERROR(read_transform(dir.file("none.yaml")), dir.file("none.yaml"), "missing file");
}

}  // namespace
}  // namespace l2s::io
