// Calibrates a dataset folder with the Calibrator facade, frame by frame, as a
// live system would, and prints T_lidar_camera.
//   02_calibrate_dataset DATASET [default|paper]
#include <l2s/calibrator.hpp>
#include <l2s/error.hpp>
#include <l2s/io/dataset.hpp>

#include <iostream>

int main(int argc, char** argv) {
  if (argc < 2 || argc > 3) {
    std::cerr << "usage: " << argv[0] << " DATASET [default|paper]\n";
    return 2;
  }
  try {
    const auto dataset = l2s::io::Dataset::open(argv[1]);
    const auto params = l2s::Calibrator::Params::preset(argc == 3 ? argv[2] : "default");
    l2s::Calibrator calibrator(dataset.cameras(), dataset.target(), params);
    for (std::size_t i = 0; i < dataset.size(); ++i) {
      const auto frame = dataset.load(i);
      const auto report = calibrator.add(frame.lidar, frame.left, frame.right, frame.stem);
      if (!report.lidar.found) std::cout << frame.stem << " lidar: " << report.lidar.reason << "\n";
      if (!report.camera.found) std::cout << frame.stem << " camera: " << report.camera.reason << "\n";
    }
    const auto result = calibrator.result();
    if (!result.found) {
      std::cerr << "calibration failed: " << result.reason << "\n";
      return 1;
    }
    std::cout << "T_lidar_camera =\n" << result.T_lidar_camera.matrix() << "\n";
  } catch (const l2s::Error& error) {
    std::cerr << "error: " << error.what() << "\n";
    return 1;
  }
  return 0;
}
