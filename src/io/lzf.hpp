#pragma once
// LZF compression, the codec of PCD's binary_compressed encoding.
//
// Format (one stream of chunks, each introduced by a control byte c):
//   c < 32         literal run: the next c + 1 bytes are copied to the output;
//   c >= 32        back-reference: length L = (c >> 5) + 2, and when c >> 5 == 7
//                  one more byte is added to L; then a byte b gives the distance
//                  d = ((c & 31) << 8 | b) + 1 back from the end of the output,
//                  and L bytes are copied from there (they may overlap the copy).

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <vector>

namespace l2s::io::lzf {

/// Corrupt compressed data; the message says what went wrong.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Compresses `size` bytes (greedy matching through a hash table of 3-byte
/// prefixes). Always succeeds; incompressible data grows by at most 1/32 + 1 byte.
/// Deterministic: the same input gives the same bytes.
std::vector<std::uint8_t> compress(const std::uint8_t* data, std::size_t size);

/// Decompresses into exactly `output_size` bytes at `output`. Throws lzf::Error
/// when the stream is corrupt, overruns `output_size`, or produces fewer bytes.
void decompress(const std::uint8_t* input, std::size_t input_size, std::uint8_t* output,
                std::size_t output_size);

/// The largest output any `input_size` bytes of LZF can decompress to: a 3-byte
/// back-reference yields at most 264 bytes. Readers check sizes against it before
/// allocating, so a lying header cannot make them allocate gigabytes.
inline std::size_t max_decompressed_size(std::size_t input_size) {
  return input_size / 3 * 264 + 264;
}

}  // namespace l2s::io::lzf
