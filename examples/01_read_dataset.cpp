// Opens a dataset folder (DATASET.md) and prints what it holds, frame by frame.
//   01_read_dataset DATASET
#include <l2s/error.hpp>
#include <l2s/io/dataset.hpp>

#include <iostream>

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: " << argv[0] << " DATASET\n";
    return 2;
  }
  try {
    const auto dataset = l2s::io::Dataset::open(argv[1]);
    const auto& cameras = dataset.cameras();
    std::cout << "cameras: " << cameras.left.width << "x" << cameras.left.height
              << ", fx " << cameras.left.fx() << " px, baseline " << cameras.baseline() << " m\n"
              << "frames: " << dataset.size() << "\n";
    for (std::size_t i = 0; i < dataset.size(); ++i) {
      const auto frame = dataset.load(i);
      std::cout << frame.stem << ": " << frame.lidar.size() << " lidar points"
                << (frame.rings_recovered() ? " (rings recovered)" : "") << "\n";
    }
  } catch (const l2s::Error& error) {
    std::cerr << "error: " << error.what() << "\n";
    return 1;
  }
  return 0;
}
