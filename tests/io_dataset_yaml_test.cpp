// dataset.yaml (DATASET.md version 3): which images a folder holds, and how
// its lidar files pair with them. Strict: a misspelt key or value must not
// silently mean "rectified" or "sweeps".
#include <l2s/error.hpp>
#include <l2s/io/dataset_yaml.hpp>

#include "io_test_helpers.hpp"
#include "support/test_data.hpp"

#include <gtest/gtest.h>

namespace l2s::io {
namespace {

TEST(DatasetYaml, ReadsTheImageKind) {
  test::TempDir dir;
  const std::string path = dir.file("dataset.yaml");
  test::write_text(path, "images: raw\n");
  EXPECT_EQ(read_dataset_info(path).images, ImageKind::Raw);
  test::write_text(path, "# a comment\nimages: rectified\n");
  EXPECT_EQ(read_dataset_info(path).images, ImageKind::Rectified);
}

TEST(DatasetYaml, ReadsTheLidarForm) {
  test::TempDir dir;
  const std::string path = dir.file("dataset.yaml");
  test::write_text(path, "lidar: accumulated\n");
  EXPECT_EQ(read_dataset_info(path).lidar, LidarForm::Accumulated);
  EXPECT_EQ(read_dataset_info(path).images, ImageKind::Rectified);
  test::write_text(path, "images: raw\nlidar: sweeps\n");
  EXPECT_EQ(read_dataset_info(path).lidar, LidarForm::Sweeps);
  test::write_text(path, "images: raw\n");
  EXPECT_EQ(read_dataset_info(path).lidar, LidarForm::Sweeps);
}

TEST(DatasetYaml, EmptyOrMissingMeansRectified) {
  test::TempDir dir;
  const std::string path = dir.file("dataset.yaml");
  EXPECT_EQ(read_dataset_info_or_default(path).images, ImageKind::Rectified);
  EXPECT_FILE_ERROR(read_dataset_info(path), path, "missing file");
  test::write_text(path, "");
  EXPECT_EQ(read_dataset_info(path).images, ImageKind::Rectified);
  test::write_text(path, "# nothing but a comment\n");
  EXPECT_EQ(read_dataset_info_or_default(path).images, ImageKind::Rectified);
}

TEST(DatasetYaml, ErrorsNameTheFileAndTheKey) {
  test::TempDir dir;
  const std::string path = dir.file("dataset.yaml");
  test::write_text(path, "image: raw\n");
  EXPECT_FILE_ERROR(read_dataset_info(path), path, "unknown key 'image' (known: images, lidar)");
  test::write_text(path, "lidars: accumulated\n");
  EXPECT_FILE_ERROR(read_dataset_info(path), path, "unknown key 'lidars' (known: images, lidar)");
  test::write_text(path, "lidar: accumulate\n");
  EXPECT_FILE_ERROR(read_dataset_info(path), path, "lidar: 'accumulate' is neither sweeps nor accumulated");
  test::write_text(path, "images: raw\nversion: 2\n");
  EXPECT_FILE_ERROR(read_dataset_info(path), path, "unknown key 'version'");
  test::write_text(path, "images: distorted\n");
  EXPECT_FILE_ERROR(read_dataset_info(path), path,
                    "images: 'distorted' is neither rectified nor raw");
  test::write_text(path, "images: Raw\n");
  EXPECT_FILE_ERROR(read_dataset_info(path), path, "images: 'Raw'");
  test::write_text(path, "images: [raw]\n");
  EXPECT_FILE_ERROR(read_dataset_info(path), path, "images: expected a string");
  test::write_text(path, "- images: raw\n");
  EXPECT_FILE_ERROR(read_dataset_info(path), path, "expected a map");
  test::write_text(path, "images: [raw\n");
  EXPECT_FILE_ERROR(read_dataset_info(path), path, "malformed YAML");
}

TEST(DatasetYaml, WritesWhatItReads) {
  test::TempDir dir;
  const std::string path = dir.file("dataset.yaml");
  write_dataset_info(path, {ImageKind::Raw});
  EXPECT_EQ(test::read_bytes(path), "images: raw\n");
  EXPECT_EQ(read_dataset_info(path).images, ImageKind::Raw);
  write_dataset_info(path, {ImageKind::Rectified});
  EXPECT_EQ(read_dataset_info(path).images, ImageKind::Rectified);
  EXPECT_EQ(to_string(ImageKind::Raw), "raw");
  write_dataset_info(path, {ImageKind::Rectified, LidarForm::Accumulated});
  EXPECT_EQ(test::read_bytes(path), "images: rectified\nlidar: accumulated\n");
  EXPECT_EQ(read_dataset_info(path).lidar, LidarForm::Accumulated);
  EXPECT_EQ(to_string(LidarForm::Sweeps), "sweeps");
}

}  // namespace
}  // namespace l2s::io
