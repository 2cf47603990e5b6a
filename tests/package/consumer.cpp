// The core library from outside: its version, a transform file written and
// read back, and a Calibrator that rejects a bad image by name.
#include <l2s/calibrator.hpp>
#include <l2s/error.hpp>
#include <l2s/io/transform_yaml.hpp>
#include <l2s/version.hpp>

#include <cstdio>
#include <cstring>
#include <string>

int main(int argc, char** argv) {
  if (std::strcmp(l2s::kVersion, l2s::library_version()) != 0) {
    std::printf("headers %s, library %s\n", l2s::kVersion, l2s::library_version());
    return 1;
  }
  const std::string path = std::string(argc > 1 ? argv[1] : ".") + "/consumer_transform.yaml";
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() << 0.1, -0.2, 0.3;
  l2s::io::write_transform(path, T);
  if (!l2s::io::read_transform(path).isApprox(T)) return 1;

  l2s::StereoCamera rig;
  rig.left = l2s::CameraInfo::ideal("left", 640, 480, 500.0, 320.0, 240.0);
  rig.right = l2s::CameraInfo::ideal("right", 640, 480, 500.0, 320.0, 240.0, 0.12);
  l2s::Calibrator calibrator(rig, l2s::Target{});
  try {
    calibrator.add(l2s::LidarCloud{}, l2s::Image(64, 48), l2s::Image(640, 480));
    return 1;
  } catch (const l2s::InputError& error) {  // an exception type of the shared library, caught outside it
    std::printf("l2scalib %s: %s\n", l2s::library_version(), error.what());
  }
  return 0;
}
