// Reading a recording: a ROS 1 bag of 1280x960 stereo pairs and HDL-64E
// sweeps (lz4 chunks of about a megabyte, as rosbag record writes them),
// read as `l2s extract` and `l2s calibrate RECORDING` read it
// (l2s::RecordedFrames: header stamps, pairing and camera_info, then the
// paired clouds and images decoded frame by frame), without writing
// anything. Throughput counts the messages' bytes; one chunk and a few
// frames are in memory at a time.
#include <l2s/recording/recorded_frames.hpp>
#include <l2s/recording/ros1_bag.hpp>
#include <l2s/sim/simulation.hpp>

#include "support/ros1_bag_writer.hpp"

#include <benchmark/benchmark.h>

#include <cstdio>
#include <filesystem>
#include <map>
#include <utility>
#include <string>

namespace {

constexpr std::int64_t kStart = 1700000000LL * 1000000000LL;

/// The bag, written once: `frames` frames of the paper's setting 1 with an
/// HDL-64E; returns its path and the bytes its messages hold.
const std::pair<std::string, std::size_t>& bag(int frames) {
  static std::map<int, std::pair<std::string, std::size_t>> made;
  auto found = made.find(frames);
  if (found != made.end()) return found->second;
  auto config = l2s::sim::SimulationConfig::paper(1, "hdl64");
  config.frames = frames;
  config.seed = 4;
  const l2s::sim::DatasetSimulator simulator(config);
  const std::vector<l2s::test::CloudField> layout = {{"x", 7}, {"y", 7}, {"z", 7}, {"intensity", 7}, {"ring", 4}, {"time", 7}};
  std::vector<l2s::test::BagMessageToWrite> messages;
  std::size_t bytes = 0;
  for (int k = 0; k < frames; ++k) {
    const auto frame = simulator.frame(k);
    const std::int64_t t = kStart + k * 100000000LL;
    messages.push_back({"/velodyne_points", "sensor_msgs/PointCloud2", t,
                        l2s::test::point_cloud2_message(frame.lidar, layout, t, "velodyne", 1, false, 32)});
    for (const auto& [side, image] : {std::pair{"left", &frame.left}, std::pair{"right", &frame.right}}) {
      const auto& i = *image;
      messages.push_back({std::string("/stereo/") + side + "/image_rect", "sensor_msgs/Image", t + 4000000,
                          l2s::test::image_message(t + 4000000, side, i.width, i.height,
                                                   i.channels == 3 ? "bgr8" : "mono8",
                                                   static_cast<std::uint32_t>(i.width * i.channels), i.pixels)});
      messages.push_back({std::string("/stereo/") + side + "/camera_info", "sensor_msgs/CameraInfo", t + 4000000,
                          l2s::test::camera_info_message(t + 4000000, side,
                                                         side == std::string("left") ? simulator.cameras().left
                                                                                     : simulator.cameras().right)});
    }
  }
  for (const auto& m : messages) bytes += m.data.size();
  const std::string path = (std::filesystem::temp_directory_path() / "l2s_recording_benchmark.bag").string();
  l2s::test::write_ros1_bag(path, messages, "lz4", 1);
  return made.emplace(frames, std::pair{path, bytes}).first->second;
}

/// Arg: frames in the bag.
void BM_ReadAndPairBag_Hdl64Stereo1280x960(benchmark::State& state) {
  const auto& [path, bytes] = bag(static_cast<int>(state.range(0)));
  std::size_t frames = 0;
  for (auto _ : state) {
    const l2s::Ros1Bag recording(path);
    const l2s::RecordedFrames recorded(recording);
    frames = 0;
    recorded.read([&](l2s::RecordedFrame&& frame) {
      benchmark::DoNotOptimize(frame.frame.lidar.size());
      benchmark::DoNotOptimize(frame.frame.left.pixels.data());
      ++frames;
      return true;
    });
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * bytes));
  state.counters["frames"] = static_cast<double>(frames);
}
BENCHMARK(BM_ReadAndPairBag_Hdl64Stereo1280x960)->Arg(5)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
