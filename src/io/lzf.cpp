// LZF codec written from the format description in lzf.hpp (compatible with
// the files PCL writes and reads).
#include "io/lzf.hpp"

#include <algorithm>
#include <string>

namespace l2s::io::lzf {
namespace {

constexpr std::size_t kMaxLiteral = 32;     // a literal run holds 1..32 bytes
constexpr std::size_t kMinMatch = 3;        // shorter matches cost more than literals
constexpr std::size_t kMaxMatch = 264;      // 2 + 7 + 255
constexpr std::size_t kMaxDistance = 8192;  // 13 bits of distance - 1
constexpr int kHashBits = 14;

std::uint32_t hash3(const std::uint8_t* p) {
  const std::uint32_t v = (std::uint32_t{p[0]} << 16) | (std::uint32_t{p[1]} << 8) | p[2];
  return (v * 2654435761u) >> (32 - kHashBits);  // Knuth's multiplicative hash
}

class Writer {
 public:
  explicit Writer(std::size_t expected) { out_.reserve(expected + expected / kMaxLiteral + 16); }

  void literal(std::uint8_t byte) {
    pending_.push_back(byte);
    if (pending_.size() == kMaxLiteral) flush();
  }

  void match(std::size_t length, std::size_t distance) {
    flush();
    const std::size_t offset = distance - 1;
    const std::size_t coded = length - 2;
    const auto high = static_cast<std::uint8_t>(offset >> 8);
    if (coded < 7) {
      out_.push_back(static_cast<std::uint8_t>(coded << 5 | high));
    } else {
      out_.push_back(static_cast<std::uint8_t>(7 << 5 | high));
      out_.push_back(static_cast<std::uint8_t>(coded - 7));
    }
    out_.push_back(static_cast<std::uint8_t>(offset & 0xff));
  }

  std::vector<std::uint8_t> finish() {
    flush();
    return std::move(out_);
  }

 private:
  void flush() {
    if (pending_.empty()) return;
    out_.push_back(static_cast<std::uint8_t>(pending_.size() - 1));
    out_.insert(out_.end(), pending_.begin(), pending_.end());
    pending_.clear();
  }

  std::vector<std::uint8_t> out_;
  std::vector<std::uint8_t> pending_;
};

}  // namespace

std::vector<std::uint8_t> compress(const std::uint8_t* data, std::size_t size) {
  // Positions + 1 of the last occurrence of each 3-byte hash (0 = none yet).
  std::vector<std::size_t> last_seen(std::size_t{1} << kHashBits, 0);
  Writer writer(size);
  std::size_t i = 0;
  while (i < size) {
    if (i + kMinMatch > size) {
      writer.literal(data[i++]);
      continue;
    }
    const std::uint32_t h = hash3(data + i);
    const std::size_t candidate = last_seen[h];
    last_seen[h] = i + 1;
    std::size_t length = 0;
    if (candidate != 0 && i - (candidate - 1) <= kMaxDistance) {
      const std::size_t from = candidate - 1;
      const std::size_t limit = std::min(kMaxMatch, size - i);
      while (length < limit && data[from + length] == data[i + length]) ++length;
    }
    if (length < kMinMatch) {
      writer.literal(data[i++]);
      continue;
    }
    writer.match(length, i - (candidate - 1));
    // Index the covered positions too, so that later data can refer into the match.
    for (std::size_t j = i + 1; j < i + length && j + kMinMatch <= size; ++j)
      last_seen[hash3(data + j)] = j + 1;
    i += length;
  }
  return writer.finish();
}

void decompress(const std::uint8_t* input, std::size_t input_size, std::uint8_t* output,
                std::size_t output_size) {
  std::size_t in = 0, out = 0;
  while (in < input_size) {
    const std::size_t control = input[in++];
    if (control < kMaxLiteral) {
      const std::size_t length = control + 1;
      if (length > input_size - in) throw Error("literal run past the end of the compressed data");
      if (length > output_size - out) throw Error("data decompresses to more bytes than expected");
      std::copy(input + in, input + in + length, output + out);
      in += length;
      out += length;
      continue;
    }
    std::size_t length = (control >> 5) + 2;
    if (length == 9) {
      if (in >= input_size) throw Error("back-reference cut off at the end of the data");
      length += input[in++];
    }
    if (in >= input_size) throw Error("back-reference cut off at the end of the data");
    const std::size_t distance = ((control & 31) << 8 | input[in++]) + 1;
    if (distance > out) throw Error("back-reference before the start of the data");
    if (length > output_size - out) throw Error("data decompresses to more bytes than expected");
    // Byte by byte: source and destination overlap for runs (distance < length).
    for (std::size_t k = 0; k < length; ++k, ++out) output[out] = output[out - distance];
  }
  if (out != output_size)
    throw Error("data decompresses to " + std::to_string(out) + " bytes, expected " +
                std::to_string(output_size));
}

}  // namespace l2s::io::lzf
