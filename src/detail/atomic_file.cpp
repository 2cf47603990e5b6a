#include "detail/atomic_file.hpp"

#include <l2s/error.hpp>

#include <atomic>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>

namespace l2s::detail {
namespace {

// Unique within the process and across processes writing the same folder.
std::string temporary_name(const std::string& path) {
  static std::atomic<unsigned long> counter{0};
  std::ostringstream name;
  name << path << ".tmp." << ::getpid() << "." << counter++;
  return name.str();
}

}  // namespace

void write_file_atomically(const std::string& path,
                           const std::function<void(std::ostream&)>& write) {
  const std::string temporary = temporary_name(path);
  try {
    {
      std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
      if (!out) throw FileError(path, "cannot open for writing");
      write(out);
      out.flush();
      if (!out) throw FileError(path, "write failed (disk full?)");
    }
    std::error_code error;
    std::filesystem::rename(temporary, path, error);
    if (error) throw FileError(path, "cannot replace file: " + error.message());
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw;
  }
}

void write_file_atomically(const std::string& path, const std::string& bytes) {
  write_file_atomically(path, [&](std::ostream& out) { out.write(bytes.data(), bytes.size()); });
}

}  // namespace l2s::detail
