#pragma once
// Shared by the fuzz targets: the readers under test take a path, so each
// input is written to one scratch file per process (in /dev/shm when there is
// one, to keep the disk out of the loop) and read back through the public API.

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <unistd.h>

namespace l2s::fuzz {

/// Path of this process's scratch file (removed at exit).
inline const std::string& scratch_path(const char* extension) {
  static const std::string path = [extension] {
    const char* dir = access("/dev/shm", W_OK) == 0 ? "/dev/shm" : "/tmp";
    std::string p = std::string(dir) + "/l2s_fuzz_" + std::to_string(getpid()) + extension;
    static std::string for_exit;
    for_exit = p;
    std::atexit([] { std::remove(for_exit.c_str()); });
    return p;
  }();
  return path;
}

/// Writes `size` bytes to the scratch file and returns its path.
inline const std::string& write_scratch(const std::uint8_t* data, std::size_t size,
                                        const char* extension) {
  const std::string& path = scratch_path(extension);
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return path;
}

}  // namespace l2s::fuzz
