// The LZF codec of binary_compressed PCD files.
#include "io/lzf.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <random>

namespace l2s::io::lzf {
namespace {

using Bytes = std::vector<std::uint8_t>;

Bytes round_trip(const Bytes& data) {
  const Bytes packed = compress(data.data(), data.size());
  EXPECT_LE(packed.size(), data.size() + data.size() / 32 + 1);
  Bytes unpacked(data.size());
  decompress(packed.data(), packed.size(), unpacked.data(), unpacked.size());
  return unpacked;
}

Bytes random_bytes(std::size_t size, unsigned seed) {
  std::mt19937 rng(seed);
  Bytes data(size);
  for (auto& b : data) b = static_cast<std::uint8_t>(rng());
  return data;
}

TEST(Lzf, RoundTripsEmptyTinyRandomAndRepetitiveData) {
  EXPECT_EQ(round_trip({}), Bytes{});
  EXPECT_EQ(round_trip({42}), Bytes{42});
  EXPECT_EQ(round_trip({1, 2}), (Bytes{1, 2}));
  EXPECT_EQ(round_trip({7, 7, 7, 7, 7, 7, 7, 7, 7, 7}), Bytes(10, 7));
  const Bytes noise = random_bytes(100000, 1);
  EXPECT_EQ(round_trip(noise), noise);
  Bytes zeros(300000, 0);
  EXPECT_EQ(round_trip(zeros), zeros);
  // Structured data like the columns of a point cloud, with repeats far apart.
  Bytes structured;
  for (int i = 0; i < 50000; ++i) {
    const float value = static_cast<float>(i % 977) * 0.01f;
    std::uint8_t raw[4];
    std::memcpy(raw, &value, 4);
    structured.insert(structured.end(), raw, raw + 4);
  }
  EXPECT_EQ(round_trip(structured), structured);
}

TEST(Lzf, CompressesRepetitiveDataWell) {
  const Bytes zeros(264 * 1000, 0);
  EXPECT_LT(compress(zeros.data(), zeros.size()).size(), 3100u);
  Bytes pattern;
  for (int i = 0; i < 100000; ++i) pattern.push_back(static_cast<std::uint8_t>(i % 100));
  EXPECT_LT(compress(pattern.data(), pattern.size()).size(), pattern.size() / 50);
}

TEST(Lzf, IsDeterministic) {
  const Bytes noise = random_bytes(50000, 2);
  EXPECT_EQ(compress(noise.data(), noise.size()), compress(noise.data(), noise.size()));
}

TEST(Lzf, DecodesHandWrittenStream) {
  // literal "abc"; reference distance 3 length 7 (overlapping its own output);
  // long reference (length 9 + 3) at distance 10.
  const Bytes stream = {2, 'a', 'b', 'c', (5 << 5) | 0, 2, (7 << 5) | 0, 3, 9};
  Bytes out(3 + 7 + 12);
  decompress(stream.data(), stream.size(), out.data(), out.size());
  EXPECT_EQ(std::string(out.begin(), out.end()),
            "abcabcabca"
            "abcabcabcaab");
}

TEST(Lzf, RejectsCorruptStreams) {
  const auto fails = [&](const Bytes& stream, std::size_t expected) {
    Bytes buffer(expected);
    EXPECT_THROW(decompress(stream.data(), stream.size(), buffer.data(), buffer.size()), Error);
  };
  fails({5, 'a', 'b'}, 6);              // literal past the end of the input
  fails({0, 'a', (1 << 5) | 1, 0}, 4);  // reference before the start of the output
  fails({0, 'a', (1 << 5), 0}, 3);      // more output than expected
  fails({0, 'a'}, 2);                   // less output than expected
  fails({0, 'a', (7 << 5)}, 30);        // long reference cut off
  fails({0, 'a', (1 << 5)}, 4);         // distance byte missing
  // Random garbage never crashes, whatever it decodes to.
  for (unsigned seed = 0; seed < 200; ++seed) {
    const Bytes garbage = random_bytes(64, seed);
    Bytes buffer(256);
    try {
      decompress(garbage.data(), garbage.size(), buffer.data(), buffer.size());
    } catch (const Error&) {
    }
  }
}

TEST(Lzf, BoundsTheLargestPossibleOutput) {
  const Bytes zeros(1000000, 0);
  const Bytes packed = compress(zeros.data(), zeros.size());
  EXPECT_GE(max_decompressed_size(packed.size()), zeros.size());
}

}  // namespace
}  // namespace l2s::io::lzf
