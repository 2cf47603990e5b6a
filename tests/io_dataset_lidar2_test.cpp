// Lidar-lidar dataset folders (DATASET.md: lidar/ + lidar2/, no cameras):
// DatasetWriter::lidar_pair output read back by Dataset and by
// tools/check_dataset.py, the T_lidar_lidar2 ground truth, and bad folders.
#include <l2s/error.hpp>
#include <l2s/io/dataset.hpp>
#include <l2s/io/pcd.hpp>
#include <l2s/io/transform_yaml.hpp>
#include <l2s/pose.hpp>

#include "support/test_data.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>

namespace fs = std::filesystem;

namespace l2s::io {
namespace {

// A sweep of `beams` lasers 2 deg apart; `with_ring` false leaves the rings to recovery.
LidarCloud sweep(int beams, int seed, bool with_ring) {
  LidarCloud cloud;
  for (int beam = 0; beam < beams; ++beam)
    for (int k = 0; k < 360; ++k) {
      const double e = (-15.0 + 2.0 * beam) * M_PI / 180.0, a = (k + 0.3 * seed) * M_PI / 180.0;
      const double r = 5.0 + 0.1 * ((k * 7 + beam) % 13);
      cloud.points.emplace_back(r * std::cos(e) * std::cos(a), r * std::cos(e) * std::sin(a), r * std::sin(e));
      cloud.intensity.push_back(static_cast<float>(k % 50));
      if (with_ring) cloud.ring.push_back(static_cast<std::uint16_t>(beam));
    }
  return cloud;
}

Eigen::Isometry3d truth() { return pose_from_roll_pitch_yaw(0.02, -0.05, 0.3, Eigen::Vector3d(0.4, -0.7, 0.1)); }

std::string write_pair(const test::TempDir& dir, int frames) {
  const std::string folder = dir.file("pair");
  const DatasetWriter writer = DatasetWriter::lidar_pair(folder, Target{});
  for (int i = 0; i < frames; ++i) {
    Frame f;
    f.stem = "00000" + std::to_string(i);
    f.lidar = sweep(16, i, true);
    f.lidar2 = sweep(16, i + 5, false);  // written without ring: the reader recovers it
    writer.write(f);
  }
  writer.write_ground_truth_lidar2(truth());
  return folder;
}

TEST(LidarPairDataset, WrittenFolderReadsBack) {
  test::TempDir dir;
  const Dataset dataset = Dataset::open(write_pair(dir, 3));
  EXPECT_TRUE(dataset.has_lidar2());
  ASSERT_EQ(dataset.size(), 3u);
  EXPECT_EQ(dataset.stems()[2], "000002");
  EXPECT_FALSE(fs::exists(dataset.folder() + "/left.yaml"));
  const Frame frame = dataset.load(1);
  EXPECT_TRUE(frame.left.empty());
  const LidarCloud expected = sweep(16, 1, true), expected2 = sweep(16, 6, false);
  ASSERT_EQ(frame.lidar.size(), expected.size());
  ASSERT_EQ(frame.lidar2.size(), expected2.size());
  EXPECT_NEAR((frame.lidar2.points[100] - expected2.points[100]).norm(), 0.0, 1e-5);  // float32 on disk
  EXPECT_EQ(frame.lidar.ring, expected.ring);
  // lidar2 had no ring field: recovered from its elevations, as for lidar/.
  EXPECT_TRUE(frame.lidar2.has_ring());
  EXPECT_NE(frame.lidar2_ring_source, RingSource::Field);
  ASSERT_TRUE(dataset.ground_truth());
  EXPECT_POSE_NEAR(*dataset.ground_truth(), truth(), 1e-9, 1e-12);
  EXPECT_EQ(transform_key(dataset.folder() + "/ground_truth.yaml"), "T_lidar_lidar2");
}

TEST(LidarPairDataset, OutputPassesCheckDatasetScript) {
  L2S_NEED_DATASET_CHECKER();
  test::TempDir dir;
  const std::string folder = write_pair(dir, 2);
  const std::string command =
      "/usr/bin/python3 " + test::dataset_checker() + " " + folder + " > " + dir.file("check.log") + " 2>&1";
  EXPECT_EQ(std::system(command.c_str()), 0) << test::read_bytes(dir.file("check.log"));
  fs::remove(folder + "/lidar2/000001.pcd");  // the script must be able to fail too
  EXPECT_NE(std::system(command.c_str()), 0);
}

TEST(LidarPairDataset, MismatchedStemsAreAFileErrorNamingLidar2) {
  test::TempDir dir;
  const std::string folder = write_pair(dir, 3);
  fs::rename(folder + "/lidar2/000002.pcd", folder + "/lidar2/000007.pcd");
  try {
    Dataset::open(folder);
    FAIL() << "no FileError";
  } catch (const FileError& error) {
    const std::string what = error.what();
    EXPECT_NE(what.find(folder + "/lidar2"), std::string::npos) << what;
    EXPECT_NE(what.find("000002 (no lidar2/000002.pcd)"), std::string::npos) << what;
    EXPECT_NE(what.find("000007 (no lidar/000007.pcd)"), std::string::npos) << what;
  }
}

TEST(LidarPairDataset, EmptyLidar2FolderHasNoFramesToPair) {
  test::TempDir dir;
  const std::string folder = write_pair(dir, 2);
  fs::remove_all(folder + "/lidar2");
  fs::create_directories(folder + "/lidar2");
  EXPECT_THROW(Dataset::open(folder), FileError);
}

TEST(LidarPairDataset, StereoDatasetHasNoLidar2) {
  test::TempDir dir;
  const std::string folder = write_pair(dir, 1);
  fs::remove_all(folder + "/lidar2");
  // Without lidar2/ the folder is a stereo dataset again, and needs its cameras.
  EXPECT_THROW(Dataset::open(folder), FileError);
}

}  // namespace
}  // namespace l2s::io
