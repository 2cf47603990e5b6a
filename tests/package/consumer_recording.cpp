// l2scalib::recording from outside: a file that is not a bag is named as such.
#include <l2s/error.hpp>
#include <l2s/recording/ros1_bag.hpp>

#include <cstdio>
#include <fstream>
#include <string>

int main(int argc, char** argv) {
  const std::string path = std::string(argc > 1 ? argv[1] : ".") + "/not_a.bag";
  std::ofstream(path) << "not a bag\n";
  try {
    l2s::Ros1Bag bag(path);
  } catch (const l2s::FileError& e) {
    std::printf("recording: %s\n", e.what());
    return std::string(e.what()).find("not a ROS bag") != std::string::npos ? 0 : 1;
  }
  return 1;
}
