// Fuzzes io::read_pcd. Built once per encoding (L2S_FUZZ_PCD_ENCODING): the
// input's DATA line, when it has one, is rewritten to that encoding, so each
// target spends its time in one decoder while the header is fuzzed as well.
// Contract checked: a cloud whose arrays agree in length, or a FileError that
// names the file; anything else (another exception, a crash, a sanitizer
// report, a huge allocation) is a finding.
#include <l2s/error.hpp>
#include <l2s/io/pcd.hpp>

#include "fuzz_input.hpp"

#include <cctype>
#include <cstdlib>
#include <string>

#ifndef L2S_FUZZ_PCD_ENCODING
#error "define L2S_FUZZ_PCD_ENCODING (ascii, binary or binary_compressed)"
#endif

namespace {

bool is_space(char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; }

// Rewrites the first header line whose key is DATA (any case, as the reader
// accepts it) to "DATA <encoding>".
void force_encoding(std::string& bytes, const std::string& encoding) {
  std::size_t line = 0;
  while (line < bytes.size()) {
    std::size_t end = bytes.find('\n', line);
    if (end == std::string::npos) end = bytes.size();
    std::size_t key = line;
    while (key < end && is_space(bytes[key])) ++key;
    std::size_t key_end = key;
    while (key_end < end && !is_space(bytes[key_end])) ++key_end;
    std::string word = bytes.substr(key, key_end - key);
    for (char& c : word) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    if (word == "DATA") {
      bytes.replace(key, end - key, "DATA " + encoding);
      return;
    }
    line = end + 1;
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string bytes(reinterpret_cast<const char*>(data), size);
  force_encoding(bytes, L2S_FUZZ_PCD_ENCODING);
  const std::string& path = l2s::fuzz::write_scratch(
      reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size(), ".pcd");
  try {
    const l2s::LidarCloud cloud = l2s::io::read_pcd(path);
    if (cloud.has_intensity() && cloud.intensity.size() != cloud.size()) std::abort();
    if (cloud.has_ring() && cloud.ring.size() != cloud.size()) std::abort();
  } catch (const l2s::FileError& error) {
    if (error.path() != path || std::string(error.what()).rfind(path, 0) != 0) std::abort();
  }
  return 0;
}
