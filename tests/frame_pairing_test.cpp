// From a recording's streams to frames: the topics a calibration reads, and
// each sweep paired with the images nearest its stamp, every drop reported.

#include <l2s/error.hpp>
#include <l2s/recording/frame_pairing.hpp>

#include "support/ros1_bag_writer.hpp"
#include "support/test_data.hpp"

#include <gtest/gtest.h>

#include <random>

namespace {

using l2s::pair_in_time;

constexpr std::int64_t kStart = 1700000000LL * 1000000000LL;
constexpr std::int64_t kMs = 1000000;

std::vector<std::int64_t> stamps(int count, std::int64_t period, std::int64_t offset = 0) {
  std::vector<std::int64_t> out;
  for (int k = 0; k < count; ++k) out.push_back(kStart + offset + k * period);
  return out;
}

bool mentions(const std::vector<std::string>& lines, const std::string& words) {
  for (const auto& line : lines)
    if (line.find(words) != std::string::npos) return true;
  return false;
}

TEST(PairInTime, EachSweepTakesTheNearestLeftImageAndItsRightTwin) {
  // A 10 Hz lidar, 20 Hz cameras 3 ms after its stamps, the right one 1 ms after the left.
  const auto lidar = stamps(10, 100 * kMs);
  const auto left = stamps(20, 50 * kMs, 3 * kMs);
  const auto right = stamps(20, 50 * kMs, 4 * kMs);
  const auto pairing = pair_in_time(lidar, left, right);
  EXPECT_DOUBLE_EQ(pairing.tolerance_s, 0.05);  // half the lidar's period
  ASSERT_EQ(pairing.frames.size(), 10u);
  for (std::size_t k = 0; k < 10; ++k) {
    EXPECT_EQ(pairing.frames[k].lidar, k);
    EXPECT_EQ(pairing.frames[k].left, 2 * k);
    EXPECT_EQ(pairing.frames[k].right, 2 * k);
  }
  EXPECT_TRUE(mentions(pairing.dropped, "10 left image(s) in no frame"));
  EXPECT_TRUE(mentions(pairing.dropped, "10 right image(s) in no frame"));
}

TEST(PairInTime, JitteredStampsAndADroppedImageKeepTheRestAndSayWhy) {
  std::mt19937 rng(5);
  std::uniform_int_distribution<std::int64_t> jitter(-10 * kMs, 10 * kMs);
  auto lidar = stamps(30, 100 * kMs), left = stamps(30, 100 * kMs, 20 * kMs), right = left;
  for (auto& t : lidar) t += jitter(rng);
  for (std::size_t k = 0; k < left.size(); ++k) {
    left[k] += jitter(rng);
    right[k] = left[k] + jitter(rng) / 5;  // within 2 ms of its left twin
  }
  left.erase(left.begin() + 12);  // the driver lost one left image
  const auto pairing = pair_in_time(lidar, left, right);
  EXPECT_EQ(pairing.frames.size(), 29u);
  for (const auto& frame : pairing.frames) EXPECT_NE(frame.lidar, 12u);
  ASSERT_TRUE(mentions(pairing.dropped, "nearest left image is")) << ::testing::PrintToString(pairing.dropped);
  EXPECT_TRUE(mentions(pairing.dropped, "1 right image(s) in no frame"));
}

TEST(PairInTime, AContestedImageGoesToTheNearerSweepAndAMissingTwinIsSaid) {
  // Two sweeps 30 ms apart around one image: the nearer keeps it.
  const std::vector<std::int64_t> lidar = {kStart, kStart + 30 * kMs, kStart + 200 * kMs};
  const std::vector<std::int64_t> left = {kStart + 20 * kMs, kStart + 201 * kMs};
  const std::vector<std::int64_t> right = {kStart + 20 * kMs};  // none for the second image
  const auto pairing = pair_in_time(lidar, left, right, {0.05, 0.005});
  ASSERT_EQ(pairing.frames.size(), 1u);
  EXPECT_EQ(pairing.frames[0].lidar, 1u);
  EXPECT_TRUE(mentions(pairing.dropped, "went to the nearer sweep"));
  EXPECT_TRUE(mentions(pairing.dropped, "no right image within 5.0 ms"));
}

TEST(PairInTime, AMonoCameraPairsWithoutARightImage) {
  const auto pairing = pair_in_time(stamps(5, 100 * kMs), stamps(5, 100 * kMs, 1 * kMs), {});
  EXPECT_EQ(pairing.frames.size(), 5u);
  EXPECT_TRUE(pairing.dropped.empty()) << ::testing::PrintToString(pairing.dropped);
  EXPECT_THROW(pair_in_time({}, {}, {}, {-1.0, 0.005}), l2s::ParamError);
}

/// A bag with these (topic, type) pairs, three messages each.
std::string bag_with(const l2s::test::TempDir& dir, const std::vector<std::pair<std::string, std::string>>& topics) {
  std::vector<l2s::test::BagMessageToWrite> messages;
  for (int k = 0; k < 3; ++k)
    for (const auto& [topic, type] : topics)
      messages.push_back({topic, type, kStart + k * 100 * kMs, std::vector<std::uint8_t>(16, 1)});
  const std::string path = dir.file("topics.bag");
  l2s::test::write_ros1_bag(path, messages, "none", 4);
  return path;
}

std::string error_of(const std::string& path, const l2s::RecordingTopics& given = {}) {
  try {
    l2s::choose_topics(l2s::Ros1Bag(path), given);
  } catch (const l2s::FileError& e) {
    return e.what();
  }
  return "";
}

TEST(ChooseTopics, PicksTheOneCandidateOfEachKindAndItsCameraInfo) {
  const l2s::test::TempDir dir;
  const std::string path = bag_with(dir, {{"/velodyne_points", "sensor_msgs/PointCloud2"},
                                          {"/stereo/left/image_raw", "sensor_msgs/Image"},
                                          {"/stereo/right/image_raw/compressed", "sensor_msgs/CompressedImage"},
                                          {"/stereo/left/camera_info", "sensor_msgs/CameraInfo"},
                                          {"/stereo/right/camera_info", "sensor_msgs/CameraInfo"},
                                          {"/imu", "sensor_msgs/Imu"}});
  const auto chosen = l2s::choose_topics(l2s::Ros1Bag(path));
  EXPECT_EQ(chosen.lidar, "/velodyne_points");
  EXPECT_EQ(chosen.left, "/stereo/left/image_raw");
  EXPECT_EQ(chosen.right, "/stereo/right/image_raw/compressed");
  EXPECT_EQ(chosen.left_info, "/stereo/left/camera_info");
  EXPECT_EQ(chosen.right_info, "/stereo/right/camera_info");
}

TEST(ChooseTopics, AnAmbiguousOrWrongOrUncalibratedTopicIsNamed) {
  const l2s::test::TempDir dir;
  const std::string path = bag_with(dir, {{"/front/points", "sensor_msgs/PointCloud2"},
                                          {"/top/points", "sensor_msgs/PointCloud2"},
                                          {"/camera/image_raw", "sensor_msgs/Image"}});
  const std::string ambiguous = error_of(path);
  EXPECT_NE(ambiguous.find("several point cloud topics (/front/points, /top/points)"), std::string::npos) << ambiguous;
  EXPECT_EQ(ambiguous.rfind(path + ": ", 0), 0u) << ambiguous;
  l2s::RecordingTopics given;
  given.lidar = "/top/points";
  const std::string uncalibrated = error_of(path, given);
  EXPECT_NE(uncalibrated.find("topic /camera/image_raw: images without camera_info"), std::string::npos) << uncalibrated;
  given.left = "/front/points";
  const std::string wrong = error_of(path, given);
  EXPECT_NE(wrong.find("topic /front/points (left): sensor_msgs/PointCloud2, not sensor_msgs/Image"), std::string::npos)
      << wrong;
  given.lidar2 = "/front/points";  // a lidar-lidar recording needs no camera
  given.left.clear();
  EXPECT_EQ(error_of(path, given), "");
}

}  // namespace
