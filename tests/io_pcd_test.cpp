// PCD reader and writer on their own: round trips of every encoding, field
// types and layouts of other writers, and every kind of broken file.
#include <l2s/error.hpp>
#include <l2s/io/pcd.hpp>

#include "io/lzf.hpp"
#include "io_test_helpers.hpp"
#include "support/test_data.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <sstream>

namespace l2s::io {
namespace {

const double kNaN = std::numeric_limits<double>::quiet_NaN();

LidarCloud make_cloud(std::size_t n, bool intensity, bool ring, bool nan_points) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> coordinate(-80.0, 80.0);
  LidarCloud cloud;
  for (std::size_t i = 0; i < n; ++i) {
    cloud.points.emplace_back(coordinate(rng), coordinate(rng), coordinate(rng) / 10.0);
    if (nan_points && i % 5 == 2) cloud.points.back() = Eigen::Vector3d::Constant(kNaN);
    if (intensity) cloud.intensity.push_back(static_cast<float>(i % 256) * 0.5f);
    if (ring) cloud.ring.push_back(static_cast<std::uint16_t>(i % 64));
  }
  return cloud;
}

// Points are stored as float32: the file holds the float nearest to each value.
// Compared as floats (GCC 12 -O2 may vectorize a double(float(x)) round trip away).
void expect_same_cloud(const LidarCloud& read, const LidarCloud& written) {
  ASSERT_EQ(read.size(), written.size());
  for (std::size_t i = 0; i < read.size(); ++i)
    for (int a = 0; a < 3; ++a) {
      const float expected = static_cast<float>(written.points[i][a]);
      if (std::isnan(expected)) {
        EXPECT_TRUE(std::isnan(read.points[i][a])) << "point " << i;
      } else {
        EXPECT_EQ(static_cast<float>(read.points[i][a]), expected)
            << "point " << i << " axis " << a;
      }
    }
  EXPECT_EQ(read.intensity, written.intensity);
  EXPECT_EQ(read.ring, written.ring);
}

struct RoundTripCase {
  PcdEncoding encoding;
  bool intensity, ring, nan_points;
  std::size_t points;
};

std::string case_name(const ::testing::TestParamInfo<RoundTripCase>& info) {
  const RoundTripCase& c = info.param;
  const char* encoding[] = {"Ascii", "Binary", "Compressed"};
  return std::string(encoding[static_cast<int>(c.encoding)]) + (c.intensity ? "Intensity" : "") +
         (c.ring ? "Ring" : "") + (c.nan_points ? "WithNaN" : "") + "_" + std::to_string(c.points);
}

class PcdRoundTrip : public ::testing::TestWithParam<RoundTripCase> {};

TEST_P(PcdRoundTrip, ReadsBackWhatItWrote) {
  test::TempDir dir;
  const RoundTripCase& c = GetParam();
  const LidarCloud cloud = make_cloud(c.points, c.intensity, c.ring, c.nan_points);
  write_pcd(dir.file("cloud.pcd"), cloud, c.encoding);
  expect_same_cloud(read_pcd(dir.file("cloud.pcd")), cloud);
  // Same input, same bytes.
  write_pcd(dir.file("again.pcd"), cloud, c.encoding);
  EXPECT_EQ(test::read_bytes(dir.file("cloud.pcd")), test::read_bytes(dir.file("again.pcd")));
}

std::vector<RoundTripCase> round_trip_cases() {
  std::vector<RoundTripCase> cases;
  for (PcdEncoding e : {PcdEncoding::Ascii, PcdEncoding::Binary, PcdEncoding::BinaryCompressed}) {
    cases.push_back({e, false, false, false, 0});
    cases.push_back({e, true, true, false, 0});
    cases.push_back({e, false, false, false, 1});
    cases.push_back({e, false, false, true, 1000});
    cases.push_back({e, true, false, false, 1000});
    cases.push_back({e, false, true, false, 1000});
    cases.push_back({e, true, true, true, 20000});
  }
  return cases;
}

INSTANTIATE_TEST_SUITE_P(Encodings, PcdRoundTrip, ::testing::ValuesIn(round_trip_cases()),
                         case_name);

TEST(PcdWriter, WritesTheDocumentedHeader) {
  test::TempDir dir;
  write_pcd(dir.file("c.pcd"), make_cloud(3, true, true, false), PcdEncoding::Binary);
  const std::string bytes = test::read_bytes(dir.file("c.pcd"));
  EXPECT_EQ(bytes.substr(0, bytes.find("DATA binary\n") + 12),
            "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS x y z intensity ring\n"
            "SIZE 4 4 4 4 2\nTYPE F F F F U\nCOUNT 1 1 1 1 1\nWIDTH 3\nHEIGHT 1\n"
            "VIEWPOINT 0 0 0 1 0 0 0\nPOINTS 3\nDATA binary\n");
  EXPECT_EQ(bytes.size(), bytes.find("DATA binary\n") + 12 + 3 * 18);
}

TEST(PcdWriter, RejectsAttributesOfTheWrongLength) {
  test::TempDir dir;
  LidarCloud cloud = make_cloud(4, true, true, false);
  cloud.ring.pop_back();
  EXPECT_THROW(write_pcd(dir.file("c.pcd"), cloud), ParamError);
  cloud = make_cloud(4, true, false, false);
  cloud.intensity.push_back(1.0f);
  EXPECT_THROW(write_pcd(dir.file("c.pcd"), cloud), ParamError);
}

// --- Files laid out as other writers do --------------------------------------

struct TypedField {
  std::string name;
  char type;
  int size;
  int count;
};

// Writes `value` as the field's type into `out`.
void put(std::string& out, const TypedField& f, double value) {
  char raw[8];
  switch (f.type * 16 + f.size) {
#define L2S_PUT(TYPE_CHAR, SIZE, CPP) \
  case TYPE_CHAR * 16 + SIZE: {       \
    CPP v = static_cast<CPP>(value);  \
    std::memcpy(raw, &v, SIZE);       \
    break;                            \
  }
    L2S_PUT('F', 4, float)
    L2S_PUT('F', 8, double) L2S_PUT('I', 1, std::int8_t) L2S_PUT('I', 2, std::int16_t)
        L2S_PUT('I', 4, std::int32_t) L2S_PUT('I', 8, std::int64_t) L2S_PUT('U', 1, std::uint8_t)
            L2S_PUT('U', 2, std::uint16_t) L2S_PUT('U', 4, std::uint32_t)
                L2S_PUT('U', 8, std::uint64_t)
#undef L2S_PUT
  }
  out.append(raw, f.size);
}

// A PCD whose fields have the given types; value(field, element, point) fills it.
template <typename Value>
std::string typed_pcd(const std::vector<TypedField>& fields, std::size_t width, std::size_t height,
                      const std::string& data, Value value) {
  std::string header = "# made by hand\nVERSION .7\nFIELDS";
  for (const auto& f : fields) header += " " + f.name;
  header += "\nSIZE";
  for (const auto& f : fields) header += " " + std::to_string(f.size);
  header += "\nTYPE";
  for (const auto& f : fields) header += std::string(" ") + f.type;
  header += "\nCOUNT";
  for (const auto& f : fields) header += " " + std::to_string(f.count);
  const std::size_t n = width * height;
  header += "\nWIDTH " + std::to_string(width) + "\nHEIGHT " + std::to_string(height) +
            "\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " + std::to_string(n) + "\nDATA " + data + "\n";
  std::string body;
  if (data == "ascii") {
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t k = 0; k < fields.size(); ++k)
        for (int e = 0; e < fields[k].count; ++e) {
          std::ostringstream token;
          token.precision(17);
          token << value(k, e, i);
          body += (k + e ? " " : "") + token.str();
        }
      body += "\n";
    }
  } else if (data == "binary") {
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t k = 0; k < fields.size(); ++k)
        for (int e = 0; e < fields[k].count; ++e) put(body, fields[k], value(k, e, i));
  } else {
    std::string arrays;
    for (std::size_t k = 0; k < fields.size(); ++k)
      for (std::size_t i = 0; i < n; ++i)
        for (int e = 0; e < fields[k].count; ++e) put(arrays, fields[k], value(k, e, i));
    const auto packed =
        lzf::compress(reinterpret_cast<const std::uint8_t*>(arrays.data()), arrays.size());
    const std::uint32_t sizes[2] = {static_cast<std::uint32_t>(packed.size()),
                                    static_cast<std::uint32_t>(arrays.size())};
    body.append(reinterpret_cast<const char*>(sizes), 8);
    body.append(packed.begin(), packed.end());
  }
  return header + body;
}

class PcdReaderLayouts : public ::testing::TestWithParam<std::string> {};

TEST_P(PcdReaderLayouts, ReadsAnyNumericTypeSkipsOtherFieldsAndKeepsOrganizedOrder) {
  test::TempDir dir;
  const std::vector<TypedField> fields = {
      {"rgb", 'U', 4, 1}, {"x", 'F', 8, 1},    {"normal", 'F', 4, 3},
      {"y", 'I', 4, 1},   {"z", 'I', 2, 1},    {"intensity", 'U', 1, 1},
      {"t", 'U', 8, 1},   {"ring", 'U', 1, 1}, {"label", 'I', 8, 2}};
  // Exact in every type above; the z column is in centimetres-as-int here.
  const auto value = [](std::size_t k, int e, std::size_t i) -> double {
    switch (k) {
      case 1:
        return 0.25 * static_cast<double>(i) - 3.0;
      case 3:
        return -static_cast<double>(i) * 7;
      case 4:
        return static_cast<double>(i % 300) - 150;
      case 5:
        return static_cast<double>(i % 256);
      case 7:
        return static_cast<double>(i % 32);
      default:
        return static_cast<double>(e + 1) * 3.5;
    }
  };
  const std::size_t width = 40, height = 16;
  test::write_text(dir.file("c.pcd"), typed_pcd(fields, width, height, GetParam(), value));
  const LidarCloud cloud = read_pcd(dir.file("c.pcd"));
  ASSERT_EQ(cloud.size(), width * height);
  ASSERT_TRUE(cloud.has_intensity());
  ASSERT_TRUE(cloud.has_ring());
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    EXPECT_EQ(cloud.points[i], Eigen::Vector3d(value(1, 0, i), value(3, 0, i), value(4, 0, i)));
    EXPECT_EQ(cloud.intensity[i], static_cast<float>(value(5, 0, i)));
    EXPECT_EQ(cloud.ring[i], value(7, 0, i));
  }
}

INSTANTIATE_TEST_SUITE_P(Encodings, PcdReaderLayouts,
                         ::testing::Values("ascii", "binary", "binary_compressed"));

TEST(PcdReader, AcceptsKeysInAnyOrderCommentsAndAliases) {
  test::TempDir dir;
  test::write_text(
      dir.file("c.pcd"),
      "# comment\n\nPOINTS 2\nversion 0.7\nDATA_SOURCE lidar\nTYPE F F F F U\n"
      "COUNT 1 1 1 1 1\r\nSIZE 4 4 4 4 2\nWIDTH 2\n# another\nFIELDS x y z i laser_id\n"
      "HEIGHT 1\nDATA ascii\n1 2 3 0.5 7\n# a comment line in the data\n\n+4 -5e-1 nan 1 0\n");
  const LidarCloud cloud = read_pcd(dir.file("c.pcd"));
  ASSERT_EQ(cloud.size(), 2u);
  EXPECT_EQ(cloud.points[0], Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(cloud.points[1].x(), 4.0);
  EXPECT_EQ(cloud.points[1].y(), -0.5);
  EXPECT_TRUE(std::isnan(cloud.points[1].z()));
  EXPECT_EQ(cloud.intensity, (std::vector<float>{0.5f, 1.0f}));
  EXPECT_EQ(cloud.ring, (std::vector<std::uint16_t>{7, 0}));
}

// --- Broken files --------------------------------------------------------------

std::string header(const std::string& fields, const std::string& size, const std::string& type,
                   const std::string& extra, const std::string& data) {
  return "VERSION 0.7\nFIELDS " + fields + "\nSIZE " + size + "\nTYPE " + type + "\n" + extra +
         "DATA " + data + "\n";
}

std::string valid_file(PcdEncoding encoding, std::size_t points = 50) {
  test::TempDir dir;
  write_pcd(dir.file("v.pcd"), make_cloud(points, true, true, false), encoding);
  return test::read_bytes(dir.file("v.pcd"));
}

std::string with_u32_at_data(std::string file, std::size_t word, std::uint32_t value) {
  const std::size_t data = file.find("DATA binary_compressed\n") + 23;
  std::memcpy(&file[data + 4 * word], &value, 4);
  return file;
}

struct BadPcd {
  const char* name;
  std::string bytes;
  const char* words;
};

class PcdReaderBadInput : public ::testing::TestWithParam<BadPcd> {};

TEST_P(PcdReaderBadInput, ThrowsFileErrorNamingTheFile) {
  test::TempDir dir;
  const std::string path = dir.file("broken.pcd");
  test::write_text(path, GetParam().bytes);
  EXPECT_FILE_ERROR(read_pcd(path), path, GetParam().words);
}

std::vector<BadPcd> bad_files() {
  const std::string xyz = "x y z", s4 = "4 4 4", f = "F F F";
  const std::string binary = valid_file(PcdEncoding::Binary);
  const std::string compressed = valid_file(PcdEncoding::BinaryCompressed);
  const std::string ascii = valid_file(PcdEncoding::Ascii);
  std::string flipped = compressed;
  flipped[flipped.find("DATA binary_compressed\n") + 23 + 8] = static_cast<char>(0xff);
  return {
      {"Empty", "", "no DATA line"},
      {"Garbage",
       std::string("\x89PNG\r\n\x1a\n\0\0\0\rIHDR\xff\xfe", 18) + std::string(500, '\x07'),
       "no DATA line"},
      {"NoX", header("a y z", s4, f, "WIDTH 1\nPOINTS 1\n", "ascii") + "1 2 3\n", "no field x"},
      {"NoZ", header("x y", "4 4", "F F", "WIDTH 1\nPOINTS 1\n", "ascii") + "1 2\n", "no field z"},
      {"NoFields", "VERSION 0.7\nWIDTH 1\nDATA ascii\n1 2 3\n", "FIELDS"},
      {"SizeCountMismatch", header(xyz, "4 4", f, "WIDTH 1\n", "ascii") + "1 2 3\n", "SIZE"},
      {"TypeCountMismatch", header(xyz, s4, "F F", "WIDTH 1\n", "ascii") + "1 2 3\n", "TYPE"},
      {"HalfFloat", header(xyz, "4 4 2", f, "WIDTH 1\n", "ascii") + "1 2 3\n", "not a number type"},
      {"UnknownType", header(xyz, s4, "F F Q", "WIDTH 1\n", "ascii") + "1 2 3\n",
       "not a number type"},
      {"ZeroCount", header(xyz, s4, f, "COUNT 1 0 1\nWIDTH 1\n", "ascii") + "1 2 3\n", "COUNT"},
      {"NegativeWidth", header(xyz, s4, f, "WIDTH -1\n", "ascii") + "1 2 3\n", "WIDTH"},
      {"NoWidthOrPoints", header(xyz, s4, f, "", "ascii") + "1 2 3\n", "WIDTH and POINTS"},
      {"PointsNotWidthTimesHeight", header(xyz, s4, f, "WIDTH 2\nHEIGHT 2\nPOINTS 3\n", "ascii"),
       "POINTS 3 != WIDTH * HEIGHT"},
      {"UnknownData", header(xyz, s4, f, "WIDTH 1\n", "binary_lz4") + "1 2 3\n", "binary_lz4"},
      {"AsciiTooFewPoints", header(xyz, s4, f, "WIDTH 3\n", "ascii") + "1 2 3\n4 5 6\n",
       "2 of 3 ascii points"},
      {"AsciiWrongValueCount", header(xyz, s4, f, "WIDTH 2\n", "ascii") + "1 2 3\n4 5\n",
       "line 2 has 2 values"},
      {"AsciiNotANumber", header(xyz, s4, f, "WIDTH 1\n", "ascii") + "1 two 3\n", "'two'"},
      {"AsciiHugePoints", header(xyz, s4, f, "WIDTH 4000000000000\n", "ascii") + "1 2 3\n",
       "truncated"},
      {"RingOutOfRange",
       header("x y z ring", "4 4 4 4", "F F F I", "WIDTH 1\n", "ascii") + "1 2 3 -1\n", "ring"},
      {"RingNotInteger",
       header("x y z ring", "4 4 4 4", "F F F F", "WIDTH 1\n", "ascii") + "1 2 3 2.5\n", "ring"},
      {"BinaryTruncated", binary.substr(0, binary.size() - 5), "truncated"},
      {"BinaryHugePoints",
       header(xyz, s4, f, "WIDTH 2000000000\nHEIGHT 2000000000\n", "binary") + "abc", "truncated"},
      {"BinaryWidthTimesHeightOverflows",
       header(xyz, s4, f, "WIDTH 18446744073709551615\nHEIGHT 3\n", "binary"), "overflows"},
      {"CompressedTruncated", compressed.substr(0, compressed.size() - 5), "truncated"},
      {"CompressedNoSizes", compressed.substr(0, compressed.find("DATA binary_compressed\n") + 26),
       "truncated"},
      {"CompressedSizeMismatch", with_u32_at_data(compressed, 1, 50 * 18 - 2),
       "50 points need 900"},
      {"CompressedLyingSize",
       with_u32_at_data(header(xyz, s4, f, "WIDTH 300000000\n", "binary_compressed") +
                            std::string(8, '\0') + std::string(16, '\1'),
                        1, 3600000000u),
       "cannot hold"},
      {"CompressedCorrupt", flipped, "corrupt compressed data"},
  };
}

INSTANTIATE_TEST_SUITE_P(Cases, PcdReaderBadInput, ::testing::ValuesIn(bad_files()),
                         [](const auto& info) { return std::string(info.param.name); });

TEST(PcdReader, MissingFileIsFileError) {
  test::TempDir dir;
  EXPECT_FILE_ERROR(read_pcd(dir.file("none.pcd")), dir.file("none.pcd"), "missing file");
}

// Any cut or damaged file either reads or throws FileError: no crash, no other exception.
TEST(PcdReader, SurvivesTruncationAndByteFlipsAtEveryPosition) {
  test::TempDir dir;
  std::mt19937 rng(11);
  for (PcdEncoding encoding :
       {PcdEncoding::Ascii, PcdEncoding::Binary, PcdEncoding::BinaryCompressed}) {
    const std::string good = valid_file(encoding, 20);
    for (std::size_t cut = 0; cut < good.size(); cut += 3) {
      // A new file each time: truncating a written file makes ext4 flush it (slow).
      const std::string path =
          dir.file(std::to_string(static_cast<int>(encoding)) + "_" + std::to_string(cut) + ".pcd");
      std::string damaged = good.substr(0, cut);
      if (cut % 2 && !damaged.empty()) damaged[rng() % damaged.size()] = static_cast<char>(rng());
      test::write_text(path, damaged);
      try {
        read_pcd(path);
      } catch (const FileError& e) {
        EXPECT_EQ(e.path(), path);
      }
    }
  }
}

}  // namespace
}  // namespace l2s::io
