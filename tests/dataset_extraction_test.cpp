// A recording back to a dataset folder: bags written from simulated
// datasets (rectified stereo, raw stereo with the lenses' camera_info) give
// back the same points, pixels and camera models; a lost image is reported
// and the rest kept; nothing is left behind on failure.

#include <l2s/error.hpp>
#include <l2s/io/dataset.hpp>
#include <l2s/recording/dataset_extraction.hpp>
#include <l2s/recording/ros_messages.hpp>
#include <l2s/sim/lidar_pair.hpp>
#include <l2s/sim/simulation.hpp>

#include "support/ros1_bag_writer.hpp"
#include "support/test_data.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>

namespace {

using l2s::test::BagMessageToWrite;

constexpr std::int64_t kStart = 1700000000LL * 1000000000LL;
constexpr std::int64_t kPeriod = 100000000LL;  // a 10 Hz lidar
const std::vector<l2s::test::CloudField> kLayout = {{"x", 7}, {"y", 7}, {"z", 7}, {"intensity", 7}, {"ring", 4}};

l2s::sim::SimulationConfig config(bool raw) {
  auto c = l2s::sim::SimulationConfig::paper(1, "vlp16");
  c.frames = 3;
  c.seed = 31;
  if (raw) c.rig = c.rig.with_real_lenses(l2s::sim::distortion_model_from_name("plumb_bob", "test"));
  return c;
}

std::vector<std::uint8_t> image_of(const l2s::Image& image, std::int64_t stamp, const std::string& frame) {
  return l2s::test::image_message(stamp, frame, image.width, image.height, image.channels == 3 ? "bgr8" : "mono8",
                                  static_cast<std::uint32_t>(image.width * image.channels), image.pixels);
}

/// The simulator's frames as a driver records them: sweeps at 10 Hz, each
/// camera's images 4 ms later (the right 1 ms after the left), camera_info
/// beside each image; `skip_left`: a left image the driver lost.
std::vector<BagMessageToWrite> recording(const l2s::sim::DatasetSimulator& sim, const std::string& image_name,
                                         int skip_left = -1) {
  std::vector<BagMessageToWrite> out;
  for (int k = 0; k < sim.config().frames; ++k) {
    const auto frame = sim.frame(k);
    const std::int64_t t = kStart + k * kPeriod;
    out.push_back({"/velodyne_points", "sensor_msgs/PointCloud2", t + 1000,
                   l2s::test::point_cloud2_message(frame.lidar, kLayout, t, "velodyne")});
    const std::int64_t tl = t + 4000000, tr = tl + 1000000;
    if (k != skip_left)
      out.push_back({"/stereo/left/" + image_name, "sensor_msgs/Image", tl + 1000, image_of(frame.left, tl, "left")});
    out.push_back({"/stereo/left/camera_info", "sensor_msgs/CameraInfo", tl + 1000,
                   l2s::test::camera_info_message(tl, "left", sim.cameras().left)});
    out.push_back({"/stereo/right/" + image_name, "sensor_msgs/Image", tr + 1000, image_of(frame.right, tr, "right")});
    out.push_back({"/stereo/right/camera_info", "sensor_msgs/CameraInfo", tr + 1000,
                   l2s::test::camera_info_message(tr, "right", sim.cameras().right)});
  }
  return out;
}

void expect_same_camera(const l2s::CameraInfo& read, const l2s::CameraInfo& made) {
  EXPECT_EQ(read.width, made.width);
  EXPECT_EQ(read.height, made.height);
  EXPECT_TRUE(read.projection_matrix.isApprox(made.projection_matrix, 1e-12));
  EXPECT_TRUE(read.camera_matrix.isApprox(made.camera_matrix, 1e-12));
  EXPECT_TRUE(read.rectification_matrix.isApprox(made.rectification_matrix, 1e-12));
  ASSERT_EQ(read.distortion_coefficients.size(), made.distortion_coefficients.size());
  for (std::size_t k = 0; k < made.distortion_coefficients.size(); ++k)
    EXPECT_NEAR(read.distortion_coefficients[k], made.distortion_coefficients[k], 1e-12);
}

class DatasetExtraction : public ::testing::TestWithParam<bool> {};

TEST_P(DatasetExtraction, GivesBackTheSimulatedDataset) {
  const bool raw = GetParam();
  const l2s::sim::DatasetSimulator sim(config(raw));
  const l2s::test::TempDir dir;
  const std::string bag_path = dir.file("rig.bag");
  l2s::test::write_ros1_bag(bag_path, recording(sim, raw ? "image_raw" : "image_rect"), "lz4", 4);
  const std::string folder = dir.file("dataset");
  const auto report = l2s::extract_dataset(l2s::Ros1Bag(bag_path), folder);
  EXPECT_EQ(report.frames, 3u);
  EXPECT_EQ(report.raw_images, raw);

  const auto dataset = l2s::io::Dataset::open(folder);
  ASSERT_EQ(dataset.size(), 3u);
  EXPECT_EQ(dataset.cameras().images, raw ? l2s::ImageKind::Raw : l2s::ImageKind::Rectified);
  expect_same_camera(dataset.cameras().left, sim.cameras().left);
  expect_same_camera(dataset.cameras().right, sim.cameras().right);
  for (int k = 0; k < 3; ++k) {
    const auto made = sim.frame(k);
    const auto read = dataset.load(static_cast<std::size_t>(k));
    EXPECT_EQ(read.left.pixels, made.left.pixels) << "frame " << k;
    EXPECT_EQ(read.right.pixels, made.right.pixels) << "frame " << k;
    ASSERT_EQ(read.lidar.size(), made.lidar.size());
    for (std::size_t i = 0; i < made.lidar.size(); i += 7)
      for (int a = 0; a < 3; ++a) {
        if (std::isfinite(made.lidar.points[i][a])) {
          ASSERT_FLOAT_EQ(static_cast<float>(read.lidar.points[i][a]), static_cast<float>(made.lidar.points[i][a]));
        }
      }
  }
  if (l2s::test::dataset_checker_missing().empty()) {
    const std::string command = "/usr/bin/python3 " + l2s::test::dataset_checker() + " " + folder + " >/dev/null";
    EXPECT_EQ(std::system(command.c_str()), 0) << command;
  }
}

INSTANTIATE_TEST_SUITE_P(Images, DatasetExtraction, ::testing::Values(false, true),
                         [](const auto& info) { return info.param ? "Raw" : "Rectified"; });

TEST(DatasetExtractionFaults, ALostImageIsReportedAndAFailureLeavesNothing) {
  const l2s::sim::DatasetSimulator sim(config(false));
  const l2s::test::TempDir dir;
  const std::string bag_path = dir.file("lost.bag");
  l2s::test::write_ros1_bag(bag_path, recording(sim, "image_rect", 1), "bz2", 5);
  const auto report = l2s::extract_dataset(l2s::Ros1Bag(bag_path), dir.file("dataset"));
  EXPECT_EQ(report.frames, 2u);
  ASSERT_FALSE(report.dropped.empty());
  EXPECT_NE(report.dropped.front().find("nearest left image is"), std::string::npos) << report.dropped.front();
  EXPECT_EQ(l2s::io::Dataset::open(dir.file("dataset")).size(), 2u);

  // Into a folder that is not empty: refused, and it is left as it was.
  EXPECT_THROW(l2s::extract_dataset(l2s::Ros1Bag(bag_path), dir.file("dataset")), l2s::FileError);
  // Images of another size than their camera_info: nothing written.
  auto messages = recording(sim, "image_rect");
  l2s::CameraInfo small = sim.cameras().left;
  small.width /= 2;
  for (auto& m : messages)
    if (m.topic == "/stereo/left/camera_info") m.data = l2s::test::camera_info_message(m.time_ns, "left", small);
  const std::string bad = dir.file("bad.bag");
  l2s::test::write_ros1_bag(bad, messages, "none", 5);
  try {
    l2s::extract_dataset(l2s::Ros1Bag(bad), dir.file("never"));
    FAIL() << "images of another size than their camera_info were written";
  } catch (const l2s::FileError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(bad + ": ", 0), 0u) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(dir.file("never")));
  for (const auto& entry : std::filesystem::directory_iterator(dir.path()))
    EXPECT_EQ(entry.path().filename().string().find(".partial"), std::string::npos) << entry.path();
}

// Stamps as drivers give them: the sweeps +-10 ms off their 10 Hz beat, the
// images +-5 ms off theirs; every frame still pairs with its own images.
TEST(DatasetExtractionFaults, JitteredStampsStillPairEachSweepWithItsImages) {
  const l2s::sim::DatasetSimulator sim(config(false));
  auto messages = recording(sim, "image_rect");
  const std::int64_t jitter[] = {9000000, -8000000, 6000000, -10000000, 3000000};
  int k = 0;
  for (auto& m : messages) {
    if (m.type == "sensor_msgs/CameraInfo") continue;
    const std::int64_t shift = m.topic == "/velodyne_points" ? jitter[k++ % 5] : jitter[k % 5] / 2;
    m.time_ns += shift;
    // The header stamp leads every message: seq (4 bytes), then seconds and nanoseconds.
    const std::int64_t stamp = l2s::header_stamp_ns(m.data) + shift;
    const std::uint32_t parts[2] = {static_cast<std::uint32_t>(stamp / 1000000000),
                                    static_cast<std::uint32_t>(stamp % 1000000000)};
    std::memcpy(m.data.data() + 4, parts, 8);
  }
  const l2s::test::TempDir dir;
  l2s::test::write_ros1_bag(dir.file("jitter.bag"), messages, "lz4", 5);
  const auto report = l2s::extract_dataset(l2s::Ros1Bag(dir.file("jitter.bag")), dir.file("dataset"));
  EXPECT_EQ(report.frames, 3u) << ::testing::PrintToString(report.dropped);
  const auto dataset = l2s::io::Dataset::open(dir.file("dataset"));
  for (int f = 0; f < 3; ++f)
    EXPECT_EQ(dataset.load(static_cast<std::size_t>(f)).left.pixels, sim.frame(f).left.pixels) << "frame " << f;
}

// A lidar-lidar recording: each sweep of the first lidar with the second's.
TEST(DatasetExtractionLidarPair, GivesBackBothLidarsSweeps) {
  l2s::sim::LidarPairConfig pair;
  pair.base = l2s::sim::SimulationConfig::paper(1, "vlp16");
  pair.base.frames = 2;
  pair.base.seed = 8;
  pair.lidar2 = "hdl32";
  const l2s::sim::LidarPairSimulator sim(pair);
  std::vector<BagMessageToWrite> messages;
  for (int k = 0; k < 2; ++k) {
    const auto frame = sim.frame(k);
    const std::int64_t t = kStart + k * kPeriod;
    messages.push_back({"/vlp16/points", "sensor_msgs/PointCloud2", t,
                        l2s::test::point_cloud2_message(frame.lidar, kLayout, t, "vlp16")});
    messages.push_back({"/hdl32/points", "sensor_msgs/PointCloud2", t + 20000000,
                        l2s::test::point_cloud2_message(frame.lidar2, kLayout, t + 20000000, "hdl32")});
  }
  const l2s::test::TempDir dir;
  l2s::test::write_ros1_bag(dir.file("pair.bag"), messages, "bz2", 2);
  l2s::ExtractionOptions options;
  options.topics.lidar = "/vlp16/points";
  options.topics.lidar2 = "/hdl32/points";
  const auto report = l2s::extract_dataset(l2s::Ros1Bag(dir.file("pair.bag")), dir.file("dataset"), options);
  EXPECT_EQ(report.frames, 2u) << ::testing::PrintToString(report.dropped);
  const auto dataset = l2s::io::Dataset::open(dir.file("dataset"));
  ASSERT_TRUE(dataset.has_lidar2());
  ASSERT_EQ(dataset.size(), 2u);
  for (int k = 0; k < 2; ++k) {
    const auto read = dataset.load(static_cast<std::size_t>(k));
    const auto made = sim.frame(k);
    EXPECT_EQ(read.lidar.size(), made.lidar.size());
    ASSERT_EQ(read.lidar2.size(), made.lidar2.size());
    EXPECT_EQ(read.lidar2.ring, made.lidar2.ring);
  }
}

#ifdef L2S_TOOL
TEST(L2sExtract, WritesTheFolderOrFailsWithOneLine) {
  const l2s::sim::DatasetSimulator sim(config(false));
  const l2s::test::TempDir dir;
  const std::string bag_path = dir.file("rig.bag");
  l2s::test::write_ros1_bag(bag_path, recording(sim, "image_rect"), "lz4", 4);
  const std::string command = std::string(L2S_TOOL) + " extract " + bag_path + " " + dir.file("out") + " > " +
                              dir.file("log") + " 2>&1";
  EXPECT_EQ(std::system(command.c_str()), 0) << l2s::test::read_bytes(dir.file("log"));
  const std::string log = l2s::test::read_bytes(dir.file("log"));
  EXPECT_NE(log.find("frames    3 of 3 sweeps paired"), std::string::npos) << log;
  EXPECT_EQ(l2s::io::Dataset::open(dir.file("out")).size(), 3u);
  // Again into the same folder: refused in one line.
  EXPECT_NE(std::system(command.c_str()), 0);
  const std::string refused = l2s::test::read_bytes(dir.file("log"));
  EXPECT_EQ(refused, "l2s: error: " + dir.file("out") +
                         ": exists and is not an empty folder: the dataset is written into a new one\n");
}
#endif

}  // namespace
