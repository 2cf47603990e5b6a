// ROS 1 bags read without ROS: bags written (by the test's own writer, from
// the bag format's description) with each chunk compression, holding the
// simulator's sweeps as PointCloud2 messages of the layouts drivers publish,
// read back point for point; and the faults a recording may have.

#include <l2s/error.hpp>
#include <l2s/recording/point_cloud2.hpp>
#include <l2s/recording/ros1_bag.hpp>
#include <l2s/sim/simulation.hpp>

#include "support/ros1_bag_writer.hpp"
#include "support/test_data.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>

#include <sys/wait.h>  // WEXITSTATUS of the l2s tool's run

namespace {

using l2s::LidarCloud;
using l2s::test::BagMessageToWrite;
using l2s::test::CloudField;

constexpr std::int64_t kStart = 1700000000LL * 1000000000LL + 250000000LL;  // [ns]
constexpr std::int64_t kSweepPeriod = 100000000LL;                         // 10 Hz

/// Three sweeps of a VLP-16 before the paper's board.
const std::vector<LidarCloud>& sweeps() {
  static const std::vector<LidarCloud> clouds = [] {
    auto config = l2s::sim::SimulationConfig::paper(1, "vlp16");
    config.frames = 3;
    config.seed = 21;
    const l2s::sim::DatasetSimulator simulator(config);
    std::vector<LidarCloud> out;
    for (int i = 0; i < config.frames; ++i) out.push_back(simulator.frame(i).lidar);
    return out;
  }();
  return clouds;
}

/// The layout of Velodyne's ROS driver: float32 x y z intensity, uint16
/// ring, float32 time, padded to 32 bytes.
const std::vector<CloudField> kVelodyneLayout = {
    {"x", 7}, {"y", 7}, {"z", 7}, {"intensity", 7}, {"ring", 4}, {"time", 7}};

/// Sweeps on /velodyne_points and as many stand-in images on another topic,
/// interleaved in time.
std::vector<BagMessageToWrite> recording() {
  std::vector<BagMessageToWrite> messages;
  for (std::size_t k = 0; k < sweeps().size(); ++k) {
    const std::int64_t t = kStart + static_cast<std::int64_t>(k) * kSweepPeriod;
    messages.push_back({"/velodyne_points", "sensor_msgs/PointCloud2", t,
                        l2s::test::point_cloud2_message(sweeps()[k], kVelodyneLayout, t, "velodyne", 1, false, 32)});
    messages.push_back({"/stereo/left/image_raw", "sensor_msgs/Image", t + 5000000,
                        std::vector<std::uint8_t>(1000 + k, static_cast<std::uint8_t>(k))});
  }
  return messages;
}

void expect_same_points(const LidarCloud& read, const LidarCloud& made) {
  ASSERT_EQ(read.size(), made.size());
  ASSERT_EQ(read.ring.size(), made.ring.size());
  for (std::size_t i = 0; i < made.size(); ++i) {
    for (int a = 0; a < 3; ++a) {
      const double expected = static_cast<float>(made.points[i][a]);  // the message stores float32
      if (std::isnan(expected))
        EXPECT_TRUE(std::isnan(read.points[i][a]));
      else
        ASSERT_EQ(read.points[i][a], expected) << "point " << i;
    }
    if (made.has_ring()) {
      ASSERT_EQ(read.ring[i], made.ring[i]) << "point " << i;
    }
    if (made.has_intensity()) {
      ASSERT_EQ(read.intensity[i], made.intensity[i]) << "point " << i;
    }
  }
}

class Ros1BagCompression : public ::testing::TestWithParam<const char*> {};

TEST_P(Ros1BagCompression, ReadsBackTheSimulatorsSweepsPointForPoint) {
  const l2s::test::TempDir dir;
  const std::string path = dir.file(std::string("sweeps_") + GetParam() + ".bag");
  l2s::test::write_ros1_bag(path, recording(), GetParam());
  const l2s::Ros1Bag bag(path);

  ASSERT_EQ(bag.topics().size(), 2u);
  const l2s::RecordedTopic* lidar = bag.topic("/velodyne_points");
  ASSERT_NE(lidar, nullptr);
  EXPECT_EQ(lidar->type, "sensor_msgs/PointCloud2");
  EXPECT_EQ(lidar->messages, sweeps().size());
  EXPECT_EQ(lidar->first_ns, kStart);
  EXPECT_EQ(lidar->last_ns, kStart + 2 * kSweepPeriod);
  EXPECT_EQ(bag.topic("/stereo/left/image_raw")->messages, 3u);

  std::size_t k = 0;
  bag.read({"/velodyne_points"}, [&](const l2s::RecordedMessage& message) {
    EXPECT_EQ(message.topic, "/velodyne_points");
    EXPECT_EQ(message.time_ns, kStart + static_cast<std::int64_t>(k) * kSweepPeriod);
    const l2s::PointCloud2Sweep sweep = l2s::decode_point_cloud2(message.data);
    EXPECT_EQ(sweep.frame_id, "velodyne");
    EXPECT_EQ(sweep.stamp_ns, message.time_ns);
    EXPECT_EQ(sweep.fields.size(), kVelodyneLayout.size());
    EXPECT_EQ(sweep.time_field, "time");
    expect_same_points(sweep.cloud, sweeps()[k]);
    ++k;
    return true;
  });
  EXPECT_EQ(k, sweeps().size());

  // Every topic, in time order across chunks; and a visit that stops early.
  std::vector<std::int64_t> times;
  bag.read({}, [&](const l2s::RecordedMessage& message) {
    times.push_back(message.time_ns);
    return true;
  });
  EXPECT_EQ(times.size(), 6u);
  EXPECT_TRUE(std::is_sorted(times.begin(), times.end()));
  int visited = 0;
  bag.read({}, [&](const l2s::RecordedMessage&) { return ++visited < 2; });
  EXPECT_EQ(visited, 2);
}

INSTANTIATE_TEST_SUITE_P(Chunks, Ros1BagCompression, ::testing::Values("none", "bz2", "lz4"));

// The recorder's own writer: Debian's python3-rosbag (scripts/setup.sh
// installs it) writes the same sweeps, as raw PointCloud2 messages, with each
// compression. Skipped where it cannot run, unless L2S_REQUIRE_SHARED=1 (CI).
TEST(Ros1Bag, ReadsWhatRosOwnBagWriterWrote) {
  if (std::system("/usr/bin/python3 -c 'import rosbag' >/dev/null 2>&1") != 0) {
    if (l2s::test::shared_required()) FAIL() << "needs /usr/bin/python3 with rosbag (python3-rosbag)";
    GTEST_SKIP() << "needs /usr/bin/python3 with rosbag (python3-rosbag)";
  }
  const l2s::test::TempDir dir;
  for (std::size_t k = 0; k < sweeps().size(); ++k) {
    const auto message = l2s::test::point_cloud2_message(sweeps()[k], kVelodyneLayout, kStart, "velodyne", 1, false, 32);
    std::ofstream(dir.file("sweep" + std::to_string(k)), std::ios::binary)
        .write(reinterpret_cast<const char*>(message.data()), static_cast<std::streamsize>(message.size()));
  }
  l2s::test::write_text(dir.file("write.py"), R"(import rosbag, rospy, sys
class PointCloud2:
    _type = "sensor_msgs/PointCloud2"
    _md5sum = "1158d486dd51d683ce2f1be655c3c181"
    _full_text = "std_msgs/Header header\nuint32 height\nuint32 width\nPointField[] fields\n..."
folder, count = sys.argv[1], int(sys.argv[2])
for compression in ("none", "bz2", "lz4"):
    with rosbag.Bag(folder + "/ros_" + compression + ".bag", "w", compression=compression, chunk_threshold=200000) as bag:
        for k in range(count):
            data = open(folder + "/sweep" + str(k), "rb").read()
            t = rospy.Time(1700000000, 250000000 + 100000000 * k)
            bag.write("/velodyne_points", (PointCloud2._type, data, PointCloud2._md5sum, None, PointCloud2), t, raw=True)
)");
  const std::string command = "/usr/bin/python3 " + dir.file("write.py") + " " + dir.path() + " " +
                              std::to_string(sweeps().size());
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  for (const char* compression : {"none", "bz2", "lz4"}) {
    SCOPED_TRACE(compression);
    const l2s::Ros1Bag bag(dir.file(std::string("ros_") + compression + ".bag"));
    ASSERT_NE(bag.topic("/velodyne_points"), nullptr);
    EXPECT_EQ(bag.topic("/velodyne_points")->messages, sweeps().size());
    EXPECT_EQ(bag.topic("/velodyne_points")->first_ns, kStart);
    std::size_t k = 0;
    bag.read({"/velodyne_points"}, [&](const l2s::RecordedMessage& message) {
      EXPECT_EQ(message.time_ns, kStart + static_cast<std::int64_t>(k) * kSweepPeriod);
      expect_same_points(l2s::decode_point_cloud2(message.data).cloud, sweeps()[k]);
      ++k;
      return true;
    });
    EXPECT_EQ(k, sweeps().size());
  }
}

TEST(PointCloud2, DecodesAnOrganisedBigEndianCloudOfDoublesWithOtherFieldNames) {
  // 16 rows, float64 big-endian coordinates, `i` for intensity, `laser_id`
  // for the ring as uint8, uint32 `t` (ns from the sweep's start, as Ouster's driver).
  const LidarCloud& made = sweeps()[0];
  const std::uint32_t rows = 16;
  LidarCloud organised = made;
  organised.points.resize(made.size() / rows * rows);
  organised.ring.resize(organised.points.size());
  organised.intensity.resize(made.has_intensity() ? organised.points.size() : 0);
  organised.points[5] = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());  // no return
  std::vector<double> times(organised.size());
  for (std::size_t i = 0; i < times.size(); ++i) times[i] = static_cast<double>(i * 1000);
  const auto message = l2s::test::point_cloud2_message(
      organised, {{"t", 6}, {"x", 8}, {"y", 8}, {"z", 8}, {"i", 7}, {"laser_id", 2}}, kStart, "os_sensor", rows,
      true, 48, times);
  const l2s::PointCloud2Sweep sweep = l2s::decode_point_cloud2(message);
  EXPECT_TRUE(sweep.big_endian);
  EXPECT_EQ(sweep.height, rows);
  EXPECT_EQ(sweep.width, organised.size() / rows);
  ASSERT_EQ(sweep.cloud.size(), organised.size());
  EXPECT_TRUE(std::isnan(sweep.cloud.points[5].x()));
  for (std::size_t i = 0; i < organised.size(); ++i) {
    if (i == 5) continue;
    ASSERT_EQ(sweep.cloud.points[i], organised.points[i]) << "point " << i;
    ASSERT_EQ(sweep.cloud.ring[i], organised.ring[i]);
  }
  EXPECT_EQ(sweep.time_field, "t");
  ASSERT_EQ(sweep.point_times.size(), times.size());
  EXPECT_EQ(sweep.point_times.back(), times.back());
}

TEST(PointCloud2, AMessageCutShortOrWithoutCoordinatesIsNamedAsSuch) {
  auto message = l2s::test::point_cloud2_message(sweeps()[0], kVelodyneLayout, kStart, "velodyne");
  message.resize(message.size() / 2);
  try {
    l2s::decode_point_cloud2(message);
    FAIL() << "a message cut in half was decoded";
  } catch (const l2s::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("PointCloud2 message: cut short"), std::string::npos) << e.what();
  }
  const auto flat = l2s::test::point_cloud2_message(sweeps()[0], {{"x", 7}, {"y", 7}, {"intensity", 7}}, kStart, "v");
  EXPECT_THROW(l2s::decode_point_cloud2(flat), l2s::InputError);
}

/// The message of `call`'s FileError, or a failure when it throws none.
template <typename Call>
std::string file_error(Call call) {
  try {
    call();
  } catch (const l2s::FileError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no FileError";
  return "";
}

TEST(Ros1Bag, ATruncatedBagFailsWithOneLineNamingTheFile) {
  const l2s::test::TempDir dir;
  const std::string path = dir.file("truncated.bag");
  l2s::test::write_ros1_bag(path, recording(), "lz4");
  std::ifstream in(path, std::ios::binary);
  std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string cut = dir.file("cut.bag");
  std::ofstream(cut, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size() * 2 / 3));
  const std::string message = file_error([&] { l2s::Ros1Bag bag(cut); });
  EXPECT_EQ(message.rfind(cut + ": truncated", 0), 0u) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

TEST(Ros1Bag, AnUnknownCompressionOrACorruptChunkIsNamed) {
  const l2s::test::TempDir dir;
  const std::string zstd = dir.file("zstd.bag");
  l2s::test::write_ros1_bag(zstd, recording(), "zstd");
  const l2s::Ros1Bag bag(zstd);  // the index holds no compressed data
  const std::string unknown = file_error([&] { bag.read({}, [](const l2s::RecordedMessage&) { return true; }); });
  EXPECT_NE(unknown.find("compression 'zstd' is not one of none, bz2, lz4"), std::string::npos) << unknown;

  const std::string path = dir.file("corrupt.bag");
  l2s::test::write_ros1_bag(path, recording(), "bz2", 6);
  std::fstream file(path, std::ios::binary | std::ios::in | std::ios::out);
  file.seekp(4096 + 13 + 200);  // inside the one chunk's compressed data
  file.write("garbage!", 8);
  file.close();
  const l2s::Ros1Bag corrupt(path);
  const std::string bad = file_error([&] { corrupt.read({}, [](const l2s::RecordedMessage&) { return true; }); });
  EXPECT_NE(bad.find(path + ": the chunk at byte"), std::string::npos) << bad;
  EXPECT_NE(bad.find("bz2"), std::string::npos) << bad;
}

TEST(Ros1Bag, AFileThatIsNotABagOrHasNoIndexIsNamed) {
  const l2s::test::TempDir dir;
  const std::string text = dir.file("not_a_bag.bag");
  std::ofstream(text) << "timestamp,x,y,z\n";
  EXPECT_NE(file_error([&] { l2s::Ros1Bag bag(text); }).find("not a ROS bag"), std::string::npos);
  const std::string ros2 = dir.file("v1.bag");
  std::ofstream(ros2) << "#ROSBAG V1.2\nabcdefgh";
  EXPECT_NE(file_error([&] { l2s::Ros1Bag bag(ros2); }).find("only version 2.0"), std::string::npos);
}

#ifdef L2S_TOOL
/// Runs `command` through the shell; its exit code and what it printed (stdout and stderr).
std::pair<int, std::string> run(const std::string& command) {
  std::string output;
  std::FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  char buffer[4096];
  while (pipe && std::fgets(buffer, sizeof buffer, pipe)) output += buffer;
  const int status = pipe ? pclose(pipe) : -1;
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, output};
}

TEST(L2sInfo, ListsARecordingsTopicsAndFailsOnATruncatedOneWithOneLine) {
  const l2s::test::TempDir dir;
  const std::string path = dir.file("sweeps.bag");
  l2s::test::write_ros1_bag(path, recording(), "lz4");
  const auto [code, text] = run(std::string(L2S_TOOL) + " info " + path);
  EXPECT_EQ(code, 0) << text;
  EXPECT_NE(text.find("/velodyne_points"), std::string::npos) << text;
  EXPECT_NE(text.find("sensor_msgs/PointCloud2"), std::string::npos) << text;
  EXPECT_NE(text.find("3 messages, 10.00 Hz"), std::string::npos) << text;
  EXPECT_NE(text.find("fields: x float32, y float32, z float32, intensity float32, ring uint16, time float32"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("/stereo/left/image_raw"), std::string::npos) << text;
  EXPECT_NE(text.find("picks     nothing: topic /stereo/left/image_raw: images without camera_info"), std::string::npos)
      << text;

  const std::string bytes = l2s::test::read_bytes(path);
  const std::string cut = dir.file("cut.bag");
  l2s::test::write_text(cut, bytes.substr(0, bytes.size() / 2));
  const auto [failed, message] = run(std::string(L2S_TOOL) + " info " + cut);
  EXPECT_EQ(failed, 1) << message;
  EXPECT_EQ(message.rfind("l2s: error: " + cut + ": truncated", 0), 0u) << message;
  EXPECT_EQ(std::count(message.begin(), message.end(), '\n'), 1) << message;
}
#endif

}  // namespace
