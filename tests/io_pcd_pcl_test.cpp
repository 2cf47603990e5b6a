// Cross-checks against PCL itself: files PCL writes read identically with ours,
// and files we write read identically with PCL, in all three encodings.
#define PCL_NO_PRECOMPILE
#include <l2s/io/pcd.hpp>

#include "support/test_data.hpp"

#include <gtest/gtest.h>
#include <pcl/conversions.h>
#include <pcl/io/pcd_io.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <cmath>
#include <limits>
#include <random>

// A Velodyne-style point, as the ROS velodyne driver publishes it.
struct PointXYZIR {
  PCL_ADD_POINT4D;
  float intensity;
  std::uint16_t ring;
  PCL_MAKE_ALIGNED_OPERATOR_NEW
} EIGEN_ALIGN16;
POINT_CLOUD_REGISTER_POINT_STRUCT(PointXYZIR,
                                  (float, x, x)(float, y, y)(float, z, z)(float, intensity,
                                                                          intensity)(std::uint16_t,
                                                                                     ring, ring))

namespace l2s::io {
namespace {

const float kNaN = std::numeric_limits<float>::quiet_NaN();

std::string name_of(const ::testing::TestParamInfo<PcdEncoding>& info) {
  const char* names[] = {"Ascii", "Binary", "BinaryCompressed"};
  return names[static_cast<int>(info.param)];
}

template <typename PointT>
void save_with_pcl(const std::string& path, const pcl::PointCloud<PointT>& cloud,
                   PcdEncoding encoding) {
  pcl::PCDWriter writer;
  int status = 0;
  switch (encoding) {
    case PcdEncoding::Ascii:
      status = writer.writeASCII(path, cloud);
      break;
    case PcdEncoding::Binary:
      status = writer.writeBinary(path, cloud);
      break;
    default:
      status = writer.writeBinaryCompressed(path, cloud);
      break;
  }
  ASSERT_EQ(status, 0) << path;
}

template <typename PointT>
pcl::PointCloud<PointT> load_with_pcl(const std::string& path) {
  pcl::PointCloud<PointT> cloud;
  EXPECT_EQ(pcl::io::loadPCDFile(path, cloud), 0) << path;
  return cloud;
}

template <typename PointT>
pcl::PointCloud<PointT> sweep(std::size_t width, std::size_t height) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> coordinate(-60.0f, 60.0f);
  pcl::PointCloud<PointT> cloud;
  cloud.width = static_cast<std::uint32_t>(width);
  cloud.height = static_cast<std::uint32_t>(height);
  cloud.is_dense = false;
  cloud.resize(width * height);
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    PointT& p = cloud[i];
    p.x = coordinate(rng);
    p.y = coordinate(rng) * 1e-3f;
    p.z = i % 7 == 3 ? kNaN : coordinate(rng) / 9.0f;
    if constexpr (!std::is_same_v<PointT, pcl::PointXYZ>)
      p.intensity = static_cast<float>(i % 100) / 3.0f;
    if constexpr (std::is_same_v<PointT, PointXYZIR>) p.ring = static_cast<std::uint16_t>(i % 32);
  }
  return cloud;
}

// Compared as float32, the type in the files: a value we hold as double must be
// the float PCL holds. (Not as double(float(x)): GCC 12 -O2 vectorizes that
// round trip away for pairs of coordinates.)
bool same(double ours, float pcl_value) {
  return std::isnan(pcl_value) ? std::isnan(ours) : static_cast<float>(ours) == pcl_value;
}

template <typename PointT>
void expect_same(const LidarCloud& ours, const pcl::PointCloud<PointT>& theirs) {
  ASSERT_EQ(ours.size(), theirs.size());
  for (std::size_t i = 0; i < ours.size(); ++i) {
    EXPECT_TRUE(same(ours.points[i].x(), theirs[i].x)) << i;
    EXPECT_TRUE(same(ours.points[i].y(), theirs[i].y)) << i;
    EXPECT_TRUE(same(ours.points[i].z(), theirs[i].z)) << i;
    if constexpr (!std::is_same_v<PointT, pcl::PointXYZ>) {
      ASSERT_TRUE(ours.has_intensity());
      EXPECT_EQ(ours.intensity[i], theirs[i].intensity) << i;
    }
    if constexpr (std::is_same_v<PointT, PointXYZIR>) {
      ASSERT_TRUE(ours.has_ring());
      EXPECT_EQ(ours.ring[i], theirs[i].ring) << i;
    }
  }
}

class PcdReaderAgainstPcl : public ::testing::TestWithParam<PcdEncoding> {};

TEST_P(PcdReaderAgainstPcl, ReadsPointXYZIWrittenByPcl) {
  test::TempDir dir;
  const std::string path = dir.file("xyzi.pcd");
  save_with_pcl(path, sweep<pcl::PointXYZI>(1000, 1), GetParam());
  const LidarCloud ours = read_pcd(path);
  EXPECT_FALSE(ours.has_ring());
  expect_same(ours, load_with_pcl<pcl::PointXYZI>(path));
}

TEST_P(PcdReaderAgainstPcl, ReadsPointWithRingWrittenByPcl) {
  test::TempDir dir;
  const std::string path = dir.file("xyzir.pcd");
  const auto cloud = sweep<PointXYZIR>(2000, 1);
  save_with_pcl(path, cloud, GetParam());
  const LidarCloud ours = read_pcd(path);
  expect_same(ours, load_with_pcl<PointXYZIR>(path));
  if (GetParam() != PcdEncoding::Ascii) expect_same(ours, cloud);  // binary is exact
}

TEST_P(PcdReaderAgainstPcl, ReadsOrganizedCloudWrittenByPcl) {
  test::TempDir dir;
  const std::string path = dir.file("organized.pcd");
  save_with_pcl(path, sweep<pcl::PointXYZ>(64, 16), GetParam());
  const LidarCloud ours = read_pcd(path);
  EXPECT_FALSE(ours.has_intensity());
  expect_same(ours, load_with_pcl<pcl::PointXYZ>(path));
}

TEST_P(PcdReaderAgainstPcl, SkipsTheExtraFieldsOfPointXYZRGBNormal) {
  test::TempDir dir;
  const std::string path = dir.file("normals.pcd");
  pcl::PointCloud<pcl::PointXYZRGBNormal> cloud;
  const auto xyz = sweep<pcl::PointXYZ>(300, 1);
  for (const auto& p : xyz) {
    pcl::PointXYZRGBNormal q;
    q.x = p.x, q.y = p.y, q.z = p.z;
    q.r = 10, q.g = 20, q.b = 30;
    q.normal_x = 1.0f, q.normal_y = 0.0f, q.normal_z = 0.0f, q.curvature = 0.5f;
    cloud.push_back(q);
  }
  save_with_pcl(path, cloud, GetParam());
  const LidarCloud ours = read_pcd(path);
  EXPECT_FALSE(ours.has_intensity());
  expect_same(ours, load_with_pcl<pcl::PointXYZ>(path));
  if (GetParam() != PcdEncoding::Ascii) expect_same(ours, xyz);
}

INSTANTIATE_TEST_SUITE_P(Encodings, PcdReaderAgainstPcl,
                         ::testing::Values(PcdEncoding::Ascii, PcdEncoding::Binary,
                                           PcdEncoding::BinaryCompressed),
                         name_of);

LidarCloud our_sweep(std::size_t n, bool attributes) {
  LidarCloud cloud;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> coordinate(-50.0, 50.0);
  for (std::size_t i = 0; i < n; ++i) {
    cloud.points.emplace_back(coordinate(rng), coordinate(rng), i % 9 == 4 ? NAN : coordinate(rng));
    if (attributes) {
      cloud.intensity.push_back(static_cast<float>(coordinate(rng)));
      cloud.ring.push_back(static_cast<std::uint16_t>(i % 128));
    }
  }
  return cloud;
}

class PcdWriterAgainstPcl : public ::testing::TestWithParam<PcdEncoding> {};

TEST_P(PcdWriterAgainstPcl, WritesFilesPclReadsIdentically) {
  test::TempDir dir;
  const std::string path = dir.file("ours.pcd");
  const LidarCloud cloud = our_sweep(3000, true);
  write_pcd(path, cloud, GetParam());

  pcl::PCLPointCloud2 blob;
  ASSERT_EQ(pcl::io::loadPCDFile(path, blob), 0);
  EXPECT_EQ(blob.width, cloud.size());
  EXPECT_EQ(blob.height, 1u);
  ASSERT_EQ(blob.fields.size(), 5u);
  const std::pair<const char*, std::uint8_t> expected[] = {
      {"x", pcl::PCLPointField::FLOAT32},
      {"y", pcl::PCLPointField::FLOAT32},
      {"z", pcl::PCLPointField::FLOAT32},
      {"intensity", pcl::PCLPointField::FLOAT32},
      {"ring", pcl::PCLPointField::UINT16}};
  for (std::size_t f = 0; f < 5; ++f) {
    EXPECT_EQ(blob.fields[f].name, expected[f].first);
    EXPECT_EQ(blob.fields[f].datatype, expected[f].second);
  }
  pcl::PointCloud<PointXYZIR> theirs;
  pcl::fromPCLPointCloud2(blob, theirs);
  expect_same(read_pcd(path), theirs);
  expect_same(cloud, theirs);
}

TEST_P(PcdWriterAgainstPcl, WritesXyzOnlyFilesPclReads) {
  test::TempDir dir;
  const std::string path = dir.file("xyz.pcd");
  LidarCloud cloud = our_sweep(500, false);
  write_pcd(path, cloud, GetParam());
  pcl::PCLPointCloud2 blob;
  ASSERT_EQ(pcl::io::loadPCDFile(path, blob), 0);
  ASSERT_EQ(blob.fields.size(), 3u);
  pcl::PointCloud<pcl::PointXYZ> theirs;
  pcl::fromPCLPointCloud2(blob, theirs);
  expect_same(cloud, theirs);
}

TEST_P(PcdWriterAgainstPcl, WritesEmptyCloudsPclReads) {
  test::TempDir dir;
  const std::string path = dir.file("empty.pcd");
  write_pcd(path, LidarCloud{}, GetParam());
  pcl::PCLPointCloud2 blob;
  ASSERT_EQ(pcl::io::loadPCDFile(path, blob), 0);
  EXPECT_EQ(blob.width * blob.height, 0u);
  EXPECT_TRUE(read_pcd(path).empty());
}

INSTANTIATE_TEST_SUITE_P(Encodings, PcdWriterAgainstPcl,
                         ::testing::Values(PcdEncoding::Ascii, PcdEncoding::Binary,
                                           PcdEncoding::BinaryCompressed),
                         name_of);

}  // namespace
}  // namespace l2s::io
