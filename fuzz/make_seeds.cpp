// Writes the seed corpus of every fuzz target (fuzz/corpus/<target>/) from
// simulated data, so the seeds are real files of each kind and can be made
// again: make_seeds fuzz/corpus
//
// PCD seeds are small (<= 64 points: the fuzzer mutates a few KB quickly) and
// cover what real files hold: x y z only, intensity and ring, PCL's padding
// fields ("_"), organised clouds, other names and types (laser_id, i, F8, U1).
// The Calibrator::add seeds are whole board scenes cropped to 2 m around the
// board, in calibrator_add_fuzzer.cpp's record layout.
#include <l2s/frame_inspector.hpp>
#include <l2s/io/calibrator_yaml.hpp>
#include <l2s/io/camera_yaml.hpp>
#include <l2s/io/pcd.hpp>
#include <l2s/io/target_yaml.hpp>
#include <l2s/io/transform_yaml.hpp>
#include <l2s/sim/simulation.hpp>

#include "io/lzf.hpp"
#if L2S_SEEDS_RECORDING
#include "support/ros1_bag_writer.hpp"

#include <opencv2/imgcodecs.hpp>
#endif

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

namespace fs = std::filesystem;
using namespace l2s;

namespace {

struct FieldSpec {
  std::string name;
  char type;
  int size;
  int count;
};

void write_bytes(const fs::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

// One value of a field for point k: x y z, intensity/i, ring/laser_id, else 0.
double value_of(const LidarCloud& cloud, std::size_t k, const std::string& name) {
  if (name == "x" || name == "y" || name == "z") return cloud.points[k][name[0] - 'x'];
  if (name == "intensity" || name == "i") return cloud.has_intensity() ? cloud.intensity[k] : 0.0;
  if (name == "ring" || name == "laser_id") return cloud.has_ring() ? cloud.ring[k] : 0.0;
  return 0.0;
}

void append_binary(std::string& out, double value, const FieldSpec& f) {
  char raw[8];
  if (f.type == 'F' && f.size == 4) { float v = static_cast<float>(value); std::memcpy(raw, &v, 4); }
  else if (f.type == 'F') std::memcpy(raw, &value, 8);
  else { std::int64_t v = static_cast<std::int64_t>(value); std::memcpy(raw, &v, 8); }  // little-endian: low bytes first
  out.append(raw, static_cast<std::size_t>(f.size));
}

// A PCD file with arbitrary fields, in any encoding, WIDTH x HEIGHT = cloud size.
std::string custom_pcd(const LidarCloud& cloud, const std::vector<FieldSpec>& fields, std::size_t width,
                       const std::string& encoding) {
  std::ostringstream header;
  header << "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS";
  for (const auto& f : fields) header << ' ' << f.name;
  header << "\nSIZE";
  for (const auto& f : fields) header << ' ' << f.size;
  header << "\nTYPE";
  for (const auto& f : fields) header << ' ' << f.type;
  header << "\nCOUNT";
  for (const auto& f : fields) header << ' ' << f.count;
  header << "\nWIDTH " << width << "\nHEIGHT " << cloud.size() / width
         << "\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " << cloud.size() << "\nDATA " << encoding << "\n";
  std::string data;
  if (encoding == "ascii") {
    std::ostringstream text;
    for (std::size_t k = 0; k < cloud.size(); ++k) {
      for (std::size_t f = 0; f < fields.size(); ++f)
        for (int c = 0; c < fields[f].count; ++c)
          text << (f + c ? " " : "") << (c == 0 ? value_of(cloud, k, fields[f].name) : 0.0);
      text << '\n';
    }
    data = text.str();
  } else if (encoding == "binary") {
    for (std::size_t k = 0; k < cloud.size(); ++k)
      for (const auto& f : fields)
        for (int c = 0; c < f.count; ++c) append_binary(data, c == 0 ? value_of(cloud, k, f.name) : 0.0, f);
  } else {
    std::string arrays;
    for (const auto& f : fields)
      for (std::size_t k = 0; k < cloud.size(); ++k)
        for (int c = 0; c < f.count; ++c) append_binary(arrays, c == 0 ? value_of(cloud, k, f.name) : 0.0, f);
    const auto packed = io::lzf::compress(reinterpret_cast<const std::uint8_t*>(arrays.data()), arrays.size());
    const std::uint32_t sizes[2] = {static_cast<std::uint32_t>(packed.size()), static_cast<std::uint32_t>(arrays.size())};
    data.append(reinterpret_cast<const char*>(sizes), 8);
    data.append(reinterpret_cast<const char*>(packed.data()), packed.size());
  }
  return header.str() + data;
}

LidarCloud first_points(const LidarCloud& cloud, std::size_t n) {
  std::vector<std::size_t> indices;
  for (std::size_t k = 0; k < cloud.size() && indices.size() < n; k += std::max<std::size_t>(1, cloud.size() / n))
    indices.push_back(k);
  return select(cloud, indices);
}

// The sweep within 2 m of the board's centre (found by the lidar branch itself).
LidarCloud around_board(const LidarCloud& sweep) {
  const LidarInspection inspection = inspect_lidar(sweep, Target{}, Calibrator::Params::preset("default"));
  if (!inspection.report.found) throw std::runtime_error("seed sweep: board not found");
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const auto& c : inspection.report.centers) centre += c / 4.0;
  std::vector<std::size_t> near;
  for (std::size_t k = 0; k < sweep.size(); ++k)
    if ((sweep.points[k] - centre).norm() < 2.0) near.push_back(k);
  return select(sweep, near);
}

std::string add_record(const LidarCloud& cloud, std::uint8_t flags) {
  std::string bytes(1, static_cast<char>(flags));
  for (std::size_t k = 0; k < cloud.size(); ++k) {
    const float xyz[3] = {static_cast<float>(cloud.points[k].x()), static_cast<float>(cloud.points[k].y()),
                          static_cast<float>(cloud.points[k].z())};
    const float intensity = cloud.has_intensity() ? cloud.intensity[k] : 0.0f;
    const std::uint16_t ring = cloud.has_ring() ? cloud.ring[k] : 0;
    bytes.append(reinterpret_cast<const char*>(xyz), 12);
    bytes.append(reinterpret_cast<const char*>(&intensity), 4);
    bytes.append(reinterpret_cast<const char*>(&ring), 2);
  }
  return bytes;
}

void pcd_seeds(const fs::path& out, const LidarCloud& sweep) {
  const LidarCloud small = first_points(sweep, 40);
  LidarCloud xyz_only = small;
  xyz_only.intensity.clear();
  xyz_only.ring.clear();
  const std::vector<FieldSpec> padded = {{"x", 'F', 4, 1}, {"y", 'F', 4, 1}, {"z", 'F', 4, 1}, {"_", 'U', 1, 4},
                                         {"intensity", 'F', 4, 1}, {"_", 'U', 1, 12}};
  const std::vector<FieldSpec> odd = {{"laser_id", 'I', 2, 1}, {"x", 'F', 8, 1}, {"y", 'F', 8, 1},
                                      {"z", 'F', 8, 1}, {"i", 'U', 1, 1}, {"normal", 'F', 4, 3}};
  const std::pair<const char*, io::PcdEncoding> encodings[] = {{"ascii", io::PcdEncoding::Ascii},
                                                               {"binary", io::PcdEncoding::Binary},
                                                               {"binary_compressed", io::PcdEncoding::BinaryCompressed}};
  for (const auto& [name, encoding] : encodings) {
    const fs::path dir = out / (std::string("pcd_") + name);
    fs::create_directories(dir);
    io::write_pcd((dir / "xyz_intensity_ring.pcd").string(), small, encoding);
    io::write_pcd((dir / "xyz.pcd").string(), xyz_only, encoding);
    io::write_pcd((dir / "empty.pcd").string(), LidarCloud{}, encoding);
    write_bytes(dir / "pcl_padded.pcd", custom_pcd(small, padded, small.size(), name));
    write_bytes(dir / "organised_odd_types.pcd", custom_pcd(small, odd, 8, name));
  }
}

void yaml_seeds(const fs::path& out, const sim::DatasetSimulator& simulator) {
  for (const char* dir : {"camera_info", "target_yaml", "params_yaml", "transform_yaml"})
    fs::create_directories(out / dir);
  io::write_camera_info((out / "camera_info/left.yaml").string(), simulator.cameras().left);
  io::write_camera_info((out / "camera_info/right.yaml").string(), simulator.cameras().right);
  io::write_target((out / "target_yaml/default.yaml").string(), Target{});
  io::write_target((out / "target_yaml/paper2017.yaml").string(), Target::paper2017());
  io::write_calibrator_params((out / "params_yaml/default.yaml").string(), Calibrator::Params::preset("default"));
  write_bytes(out / "params_yaml/paper_overrides.yaml",
              "preset: paper\nlidar_plane:\n  distance_threshold: 0.02\naccumulator:\n  min_frames: 3\nregistrar:\n  {}\n");
  io::write_transform((out / "transform_yaml/ground_truth.yaml").string(), simulator.T_lidar_camera());
  write_bytes(out / "transform_yaml/rounded.yaml",
              "T_lidar_camera:\n  rows: 4\n  cols: 4\n  data: [0.0, -1.0, 0.0, 0.1, 0.0, 0.0, -1.0, 0.2,\n"
              "         1.0, 0.0, 0.0, 0.3, 0, 0, 0, 1]\nother: {a: 1}\n");
}

#if L2S_SEEDS_RECORDING
/// Bags (each compression; a point cloud, an image and its camera_info, two
/// messages each) and single messages, behind the decoder-selecting byte of
/// ros_messages. Tiny: 30 points, 8x6 pixels.
void recording_seeds(const fs::path& out, const LidarCloud& board, const sim::DatasetSimulator& simulator) {
  fs::create_directories(out / "ros1_bag");
  fs::create_directories(out / "ros_messages");
  LidarCloud few;
  for (std::size_t i = 0; i < board.size() && few.size() < 30; i += std::max<std::size_t>(1, board.size() / 30)) {
    few.points.push_back(board.points[i]);
    if (board.has_intensity()) few.intensity.push_back(board.intensity[i]);
    if (board.has_ring()) few.ring.push_back(board.ring[i]);
  }
  const std::vector<test::CloudField> velodyne = {{"x", 7}, {"y", 7}, {"z", 7}, {"intensity", 7}, {"ring", 4}, {"time", 7}};
  const std::vector<test::CloudField> doubles = {{"t", 6}, {"x", 8}, {"y", 8}, {"z", 8}, {"i", 7}, {"laser_id", 2}};
  const std::int64_t t0 = 1700000000LL * 1000000000LL;
  std::vector<std::uint8_t> gray(8 * 6);
  for (std::size_t i = 0; i < gray.size(); ++i) gray[i] = static_cast<std::uint8_t>(i * 5);
  CameraInfo small = simulator.cameras().left;
  small.width = 8, small.height = 6;
  const auto cloud = test::point_cloud2_message(few, velodyne, t0, "velodyne");
  const auto image = test::image_message(t0, "left", 8, 6, "mono8", 8, gray);
  const auto info = test::camera_info_message(t0, "left", small);
  for (const char* compression : {"none", "bz2", "lz4"}) {
    std::vector<test::BagMessageToWrite> messages;
    for (int k = 0; k < 2; ++k) {
      messages.push_back({"/points", "sensor_msgs/PointCloud2", t0 + k * 100000000, cloud});
      messages.push_back({"/left/image_raw", "sensor_msgs/Image", t0 + k * 100000000 + 1000, image});
      messages.push_back({"/left/camera_info", "sensor_msgs/CameraInfo", t0 + k * 100000000 + 1000, info});
    }
    test::write_ros1_bag((out / "ros1_bag" / (std::string(compression) + ".bag")).string(), messages, compression, 3);
  }
  const auto seed = [&](const std::string& name, std::uint8_t decoder, const std::vector<std::uint8_t>& message) {
    std::string bytes(1, static_cast<char>(decoder));
    bytes.append(message.begin(), message.end());
    write_bytes(out / "ros_messages" / name, bytes);
  };
  seed("cloud_velodyne.bin", 0, cloud);
  LidarCloud organised = few;
  organised.points.resize(24), organised.ring.resize(24);
  organised.intensity.resize(few.has_intensity() ? 24 : 0);
  seed("cloud_organised_big_endian.bin", 0, test::point_cloud2_message(organised, doubles, t0, "os", 4, true, 48));
  seed("image_mono8.bin", 1, image);
  seed("image_bayer.bin", 1, test::image_message(t0, "left", 8, 6, "bayer_rggb8", 8, gray));
  std::vector<std::uint8_t> colour(8 * 6 * 3);
  for (std::size_t i = 0; i < colour.size(); ++i) colour[i] = static_cast<std::uint8_t>(i * 3);
  seed("image_rgb8.bin", 1, test::image_message(t0, "left", 8, 6, "rgb8", 24, colour));
  std::vector<std::uint8_t> png;
  cv::imencode(".png", cv::Mat(6, 8, CV_8UC1, gray.data()), png);
  seed("compressed_png.bin", 2, test::compressed_image_message(t0, "left", "png", png));
  seed("camera_info.bin", 3, info);
  seed("header.bin", 4, std::vector<std::uint8_t>(cloud.begin(), cloud.begin() + 24));
}
#endif

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: " << argv[0] << " CORPUS_DIR\n";
    return 2;
  }
  const fs::path out = argv[1];
  fs::create_directories(out / "calibrator_add");
  for (const auto& [setting, lidar] : {std::pair{1, "vlp16"}, std::pair{8, "hdl32"}}) {
    sim::SimulationConfig config = sim::SimulationConfig::paper(setting, lidar);
    config.frames = 1;
    const sim::DatasetSimulator simulator(config);
    const LidarCloud board = around_board(simulator.sweep(0));
    const std::string stem = std::string(lidar) + "_setting" + std::to_string(setting);
    write_bytes(out / "calibrator_add" / (stem + "_rings.bin"), add_record(board, 1 | 2));
    write_bytes(out / "calibrator_add" / (stem + "_no_rings.bin"), add_record(board, 1));
    if (setting == 1) {
      pcd_seeds(out, board);
      yaml_seeds(out, simulator);
#if L2S_SEEDS_RECORDING
      recording_seeds(out, board, simulator);
#endif
    }
  }
  std::cout << "seeds written to " << out << "\n";
  return 0;
}
