// `l2s calibrate RECORDING`: a recording written by ROS's own bag writer
// (Debian's python3-rosbag, lz4 chunks) from a simulated stereo + VLP-16
// dataset calibrates to the same transform as the dataset folder `l2s
// extract` writes from it, without writing one itself; so does a
// lidar-lidar recording.

#include <l2s/io/target_yaml.hpp>
#include <l2s/io/transform_yaml.hpp>
#include <l2s/metrics.hpp>
#include <l2s/recording/ros1_bag.hpp>
#include <l2s/sim/lidar_pair.hpp>
#include <l2s/sim/simulation.hpp>

#include "support/ros1_bag_writer.hpp"
#include "support/test_data.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace {

#ifdef L2S_TOOL
constexpr std::int64_t kStart = 1700000000LL * 1000000000LL;
constexpr std::int64_t kPeriod = 100000000LL;  // a 10 Hz lidar

/// A message for the recorder: topic, type, stamp and its serialised bytes.
struct Message {
  std::string topic, type;
  std::int64_t stamp_ns;
  std::vector<std::uint8_t> data;
};

/// The simulator's frames as a driver publishes them: sweeps at 10 Hz, the
/// rectified images 4 ms later (the right 1 ms after the left), camera_info beside each.
std::vector<Message> recording(const l2s::sim::DatasetSimulator& sim) {
  const std::vector<l2s::test::CloudField> layout = {{"x", 7}, {"y", 7}, {"z", 7}, {"intensity", 7}, {"ring", 4}};
  const auto image = [](const l2s::Image& im, std::int64_t stamp, const std::string& frame) {
    return l2s::test::image_message(stamp, frame, im.width, im.height, im.channels == 3 ? "bgr8" : "mono8",
                                    static_cast<std::uint32_t>(im.width * im.channels), im.pixels);
  };
  std::vector<Message> out;
  for (int k = 0; k < sim.config().frames; ++k) {
    const auto frame = sim.frame(k);
    const std::int64_t t = kStart + k * kPeriod, tl = t + 4000000, tr = tl + 1000000;
    out.push_back({"/velodyne_points", "PointCloud2", t, l2s::test::point_cloud2_message(frame.lidar, layout, t, "velodyne")});
    out.push_back({"/stereo/left/image_rect", "Image", tl, image(frame.left, tl, "left")});
    out.push_back({"/stereo/left/camera_info", "CameraInfo", tl,
                   l2s::test::camera_info_message(tl, "left", sim.cameras().left)});
    out.push_back({"/stereo/right/image_rect", "Image", tr, image(frame.right, tr, "right")});
    out.push_back({"/stereo/right/camera_info", "CameraInfo", tr,
                   l2s::test::camera_info_message(tr, "right", sim.cameras().right)});
  }
  return out;
}

/// Writes `messages` into `bag` with python3-rosbag, lz4-compressed, as
/// rosbag record does (raw serialised messages with their types' md5 sums).
void write_with_rosbag(const l2s::test::TempDir& dir, const std::vector<Message>& messages, const std::string& bag) {
  std::ofstream manifest(dir.file("manifest"));
  for (std::size_t m = 0; m < messages.size(); ++m) {
    const std::string name = dir.file("message" + std::to_string(m));
    std::ofstream(name, std::ios::binary)
        .write(reinterpret_cast<const char*>(messages[m].data.data()), static_cast<std::streamsize>(messages[m].data.size()));
    manifest << messages[m].topic << ' ' << messages[m].type << ' ' << messages[m].stamp_ns << ' ' << name << '\n';
  }
  manifest.close();
  l2s::test::write_text(dir.file("write.py"), R"(import rosbag, rospy, sys
md5 = {"PointCloud2": "1158d486dd51d683ce2f1be655c3c181", "Image": "060021388200f6f0f447d0fcd9c64743",
       "CameraInfo": "c9a58c1b0b154e0e6da7578cb991d214"}
def message_class(name):
    return type(name, (), {"_type": "sensor_msgs/" + name, "_md5sum": md5[name], "_full_text": ""})
classes = {name: message_class(name) for name in md5}
with rosbag.Bag(sys.argv[2], "w", compression="lz4", chunk_threshold=4000000) as bag:
    for line in open(sys.argv[1]):
        topic, kind, stamp, path = line.split()
        c = classes[kind]
        t = rospy.Time(int(stamp) // 1000000000, int(stamp) % 1000000000)
        bag.write(topic, (c._type, open(path, "rb").read(), c._md5sum, None, c), t, raw=True)
)");
  const std::string command = "/usr/bin/python3 " + dir.file("write.py") + " " + dir.file("manifest") + " " + bag;
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
}

/// Runs `l2s ARGUMENTS`; its exit status and output.
std::pair<int, std::string> l2s_run(const l2s::test::TempDir& dir, const std::string& arguments) {
  const std::string command = std::string(L2S_TOOL) + " " + arguments + " > " + dir.file("log") + " 2>&1";
  const int status = std::system(command.c_str());
  return {status, l2s::test::read_bytes(dir.file("log"))};
}

TEST(CalibrateRecording, GivesTheTransformOfItsExtractedFolder) {
  if (std::system("/usr/bin/python3 -c 'import rosbag' >/dev/null 2>&1") != 0) {
    if (l2s::test::shared_required()) FAIL() << "needs /usr/bin/python3 with rosbag (python3-rosbag)";
    GTEST_SKIP() << "needs /usr/bin/python3 with rosbag (python3-rosbag)";
  }
  auto config = l2s::sim::SimulationConfig::paper(1, "vlp16");
  config.frames = 8;
  config.seed = 5;
  const l2s::sim::DatasetSimulator sim(config);
  const l2s::test::TempDir dir;
  const std::string bag = dir.file("rig.bag");
  write_with_rosbag(dir, recording(sim), bag);
  l2s::io::write_target(dir.file("target.yaml"), config.target);

  const auto [bag_status, bag_log] =
      l2s_run(dir, "calibrate " + bag + " --target " + dir.file("target.yaml") + " -o " + dir.file("from_bag.yaml"));
  ASSERT_EQ(bag_status, 0) << bag_log;
  EXPECT_NE(bag_log.find("paired    8 of 8 sweeps"), std::string::npos) << bag_log;
  EXPECT_FALSE(std::filesystem::exists(dir.file("rig"))) << "no dataset folder is written";

  const auto [extract_status, extract_log] =
      l2s_run(dir, "extract " + bag + " " + dir.file("rig") + " --target " + dir.file("target.yaml"));
  ASSERT_EQ(extract_status, 0) << extract_log;
  const auto [folder_status, folder_log] =
      l2s_run(dir, "calibrate " + dir.file("rig") + " -o " + dir.file("from_folder.yaml"));
  ASSERT_EQ(folder_status, 0) << folder_log;

  const Eigen::Isometry3d from_bag = l2s::io::read_transform(dir.file("from_bag.yaml"));
  const Eigen::Isometry3d from_folder = l2s::io::read_transform(dir.file("from_folder.yaml"));
  const l2s::PoseError apart = l2s::pose_error(from_bag, from_folder);
  EXPECT_LT(apart.translation, 1e-4) << bag_log << folder_log;
  EXPECT_LT(apart.rotation * 180.0 / M_PI, 1e-3);
  // And it is a calibration: near the simulator's truth.
  const l2s::PoseError error = l2s::pose_error(from_bag, sim.T_lidar_camera());
  std::printf("bag vs folder: %.2e mm, %.2e deg; bag vs truth: %.2f mm, %.3f deg\n", apart.translation * 1e3,
              apart.rotation * 180.0 / M_PI, error.translation * 1e3, error.rotation * 180.0 / M_PI);
  EXPECT_LT(error.translation, 0.03) << bag_log;
  EXPECT_LT(error.rotation * 180.0 / M_PI, 0.5) << bag_log;
}

TEST(CalibrateRecording, ALidarPairRecordingGivesTheTransformOfItsExtractedFolder) {
  l2s::sim::LidarPairConfig pair;
  pair.base = l2s::sim::SimulationConfig::paper(1, "vlp16");
  pair.base.frames = 4;
  pair.base.seed = 8;
  pair.lidar2 = "hdl32";
  const l2s::sim::LidarPairSimulator sim(pair);
  const std::vector<l2s::test::CloudField> layout = {{"x", 7}, {"y", 7}, {"z", 7}, {"intensity", 7}, {"ring", 4}};
  std::vector<l2s::test::BagMessageToWrite> messages;
  for (int k = 0; k < sim.frames(); ++k) {
    const auto frame = sim.frame(k);
    const std::int64_t t = kStart + k * kPeriod, t2 = t + 20000000;  // the second lidar 20 ms later
    messages.push_back({"/vlp16/points", "sensor_msgs/PointCloud2", t,
                        l2s::test::point_cloud2_message(frame.lidar, layout, t, "vlp16")});
    messages.push_back({"/hdl32/points", "sensor_msgs/PointCloud2", t2,
                        l2s::test::point_cloud2_message(frame.lidar2, layout, t2, "hdl32")});
  }
  const l2s::test::TempDir dir;
  const std::string bag = dir.file("pair.bag");
  l2s::test::write_ros1_bag(bag, messages, "lz4", 2);
  l2s::io::write_target(dir.file("target.yaml"), pair.base.target);
  const std::string topics = " --lidar-topic /vlp16/points --lidar2-topic /hdl32/points --target " +
                             dir.file("target.yaml");

  const auto [bag_status, bag_log] = l2s_run(dir, "calibrate " + bag + topics);
  ASSERT_EQ(bag_status, 0) << bag_log;
  EXPECT_NE(bag_log.find("lidar-lidar"), std::string::npos) << bag_log;
  const auto [extract_status, extract_log] = l2s_run(dir, "extract " + bag + " " + dir.file("pair") + topics);
  ASSERT_EQ(extract_status, 0) << extract_log;
  const auto [folder_status, folder_log] =
      l2s_run(dir, "calibrate " + dir.file("pair") + " -o " + dir.file("from_folder.yaml"));
  ASSERT_EQ(folder_status, 0) << folder_log;

  // The result lands beside the recording by default.
  const std::string key = "T_lidar_lidar2";
  const l2s::PoseError apart = l2s::pose_error(l2s::io::read_transform(dir.file("pair_calibration.yaml"), key),
                                               l2s::io::read_transform(dir.file("from_folder.yaml"), key));
  EXPECT_LT(apart.translation, 1e-4) << bag_log << folder_log;
  EXPECT_LT(apart.rotation * 180.0 / M_PI, 1e-3);
  const l2s::PoseError error =
      l2s::pose_error(l2s::io::read_transform(dir.file("pair_calibration.yaml"), key), sim.T_lidar_lidar2());
  EXPECT_LT(error.translation, 0.03) << bag_log;
}

TEST(CalibrateRecording, TopicOptionsOnAFolderAreRefusedInOneLine) {
  const l2s::test::TempDir dir;
  const auto [status, log] = l2s_run(dir, "calibrate " + dir.path() + " --lidar-topic /points");
  EXPECT_NE(status, 0);
  EXPECT_NE(log.find("apply to a recording"), std::string::npos) << log;
}
#endif

}  // namespace
