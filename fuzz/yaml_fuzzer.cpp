// Fuzzes one YAML reader of l2s::io, chosen at build time (L2S_FUZZ_YAML):
//   camera_info  io::read_camera_info, then io::read_stereo_camera on the
//                input as both files (the rectified-pair checks)
//   target       io::read_target
//   params       io::read_calibrator_params
//   transform    io::read_transform (T_lidar_camera)
// Contract checked: a value, or a FileError that names the file. Any other
// exception, a crash or a sanitizer report is a finding.
#include <l2s/error.hpp>
#include <l2s/io/calibrator_yaml.hpp>
#include <l2s/io/camera_yaml.hpp>
#include <l2s/io/target_yaml.hpp>
#include <l2s/io/transform_yaml.hpp>

#include "fuzz_input.hpp"

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <string>

namespace {

void expect(bool condition) {
  if (!condition) std::abort();
}

void read(const std::string& path) {
  const std::string which = L2S_FUZZ_YAML;
  if (which == "camera_info") {
    const l2s::CameraInfo camera = l2s::io::read_camera_info(path);
    expect(camera.width > 0 && camera.height > 0 && camera.fx() > 0.0 && camera.fy() > 0.0);
    (void)l2s::io::read_stereo_camera(path, path);
  } else if (which == "target") {
    l2s::io::read_target(path).validate();  // what the reader returns is a valid board
  } else if (which == "params") {
    l2s::io::read_calibrator_params(path).validate();
  } else if (which == "transform") {
    const Eigen::Isometry3d T = l2s::io::read_transform(path);
    expect(T.matrix().allFinite());
    const double error = (T.linear().transpose() * T.linear() - Eigen::Matrix3d::Identity()).norm();
    expect(error < 1e-6 && T.linear().determinant() > 0.0);
  } else {
    std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string& path = l2s::fuzz::write_scratch(data, size, ".yaml");
  try {
    read(path);
  } catch (const l2s::FileError& error) {
    expect(error.path() == path && std::strncmp(error.what(), path.c_str(), path.size()) == 0);
  }
  return 0;
}
