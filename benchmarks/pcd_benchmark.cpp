// Reading and writing PCD sweeps: our reader and writer (src/io) against
// PCL's (pcl::PCDReader / pcl::PCDWriter through l2scalib::pcl's adapters),
// for a VLP-16 and an HDL-64E sweep in all three encodings. The README's "PCD
// files" section weighs these numbers against the fuzzing results.
// Args: lidar (16 or 64 beams), encoding (0 ascii, 1 binary, 2 binary_compressed).
#define PCL_NO_PRECOMPILE
#include <l2s/adapters/pcl.hpp>
#include <l2s/io/pcd.hpp>
#include <l2s/sim/lidar_simulator.hpp>
#include <l2s/sim/settings.hpp>

#include <benchmark/benchmark.h>
#include <pcl/console/print.h>
#include <pcl/io/pcd_io.h>

#include <filesystem>
#include <map>
#include <stdexcept>
#include <unistd.h>

namespace {

namespace fs = std::filesystem;
using l2s::io::PcdEncoding;

const l2s::LidarCloud& sweep(int beams) {
  static std::map<int, l2s::LidarCloud> sweeps;
  auto found = sweeps.find(beams);
  if (found != sweeps.end()) return found->second;
  using namespace l2s::sim;
  const Scene scene = make_scene(l2s::Target{}, BoardPose{3.0, 0.0, -0.1, 0.2, -0.06, 0.05});
  const LidarModel model = beams == 16 ? LidarModel::vlp16() : LidarModel::hdl64();
  const LidarSimulator lidar(model, LidarSimulator::Params{});
  return sweeps[beams] = lidar.sweep(RayCaster(scene), paper_setting(8).T_cambody_lidar(), 0);
}

PcdEncoding encoding_of(const benchmark::State& state) { return static_cast<PcdEncoding>(state.range(1)); }

// One file per sweep and encoding, written by our writer (PCL reads them: io_pcd_pcl_test).
const std::string& file_of(int beams, PcdEncoding encoding) {
  static std::map<std::pair<int, int>, std::string> files;
  const auto key = std::make_pair(beams, static_cast<int>(encoding));
  auto found = files.find(key);
  if (found != files.end()) return found->second;
  const fs::path dir = fs::temp_directory_path() / ("l2s_pcd_benchmark_" + std::to_string(getpid()));
  fs::create_directories(dir);
  const std::string path = (dir / (std::to_string(beams) + "_" + std::to_string(key.second) + ".pcd")).string();
  l2s::io::write_pcd(path, sweep(beams), encoding);
  return files[key] = path;
}

void label(benchmark::State& state, const std::string& path) {
  state.SetLabel(std::to_string(sweep(static_cast<int>(state.range(0))).size()) + " points, " +
                 std::to_string(fs::file_size(path) / 1024) + " KiB");
}

void BM_ReadPcd_L2s(benchmark::State& state) {
  const std::string& path = file_of(static_cast<int>(state.range(0)), encoding_of(state));
  for (auto _ : state) benchmark::DoNotOptimize(l2s::io::read_pcd(path));
  label(state, path);
}

// What a PCL-based reader costs the calibrator: PCL's read, then the adapter to a LidarCloud.
void BM_ReadPcd_Pcl(benchmark::State& state) {
  pcl::console::setVerbosityLevel(pcl::console::L_ERROR);
  const std::string& path = file_of(static_cast<int>(state.range(0)), encoding_of(state));
  pcl::PCDReader reader;
  for (auto _ : state) {
    pcl::PCLPointCloud2 cloud;
    if (reader.read(path, cloud) != 0) throw std::runtime_error("PCL cannot read " + path);
    benchmark::DoNotOptimize(l2s::adapters::from_pcl(cloud));
  }
  label(state, path);
}

void BM_WritePcd_L2s(benchmark::State& state) {
  const auto& cloud = sweep(static_cast<int>(state.range(0)));
  const std::string path = file_of(static_cast<int>(state.range(0)), encoding_of(state)) + ".l2s.pcd";
  for (auto _ : state) l2s::io::write_pcd(path, cloud, encoding_of(state));
  label(state, path);
}

void BM_WritePcd_Pcl(benchmark::State& state) {
  const auto& cloud = sweep(static_cast<int>(state.range(0)));
  const std::string path = file_of(static_cast<int>(state.range(0)), encoding_of(state)) + ".pcl.pcd";
  pcl::PCDWriter writer;
  for (auto _ : state) {
    const pcl::PCLPointCloud2 generic = l2s::adapters::to_pcl_cloud2(cloud);
    switch (encoding_of(state)) {
      case PcdEncoding::Ascii:
        writer.writeASCII(path, generic, Eigen::Vector4f::Zero(), Eigen::Quaternionf::Identity(), 8);
        break;
      case PcdEncoding::Binary:
        writer.writeBinary(path, generic);
        break;
      default:
        writer.writeBinaryCompressed(path, generic);
        break;
    }
  }
  label(state, path);
}

void sizes(benchmark::internal::Benchmark* b) {
  for (int beams : {16, 64})
    for (int encoding : {0, 1, 2}) b->Args({beams, encoding});
  b->ArgNames({"beams", "encoding"})->Unit(benchmark::kMillisecond);
}

BENCHMARK(BM_ReadPcd_L2s)->Apply(sizes);
BENCHMARK(BM_ReadPcd_Pcl)->Apply(sizes);
BENCHMARK(BM_WritePcd_L2s)->Apply(sizes);
BENCHMARK(BM_WritePcd_Pcl)->Apply(sizes);

}  // namespace
