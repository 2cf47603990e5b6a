// l2scalib::pcl: PCL clouds to LidarCloud and back, typed and generic, with
// PCL's padded layouts, organised clouds with padded rows, other field types
// and names, the other byte order, and every malformed cloud an InputError.
#define PCL_NO_PRECOMPILE
#include <l2s/adapters/pcl.hpp>
#include <l2s/error.hpp>

#include <gtest/gtest.h>
#include <pcl/conversions.h>
#include <pcl/point_types.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

// A driver-style point with a ring, as Velodyne ROS drivers register it.
struct PointXYZIR {
  PCL_ADD_POINT4D;
  float intensity;
  std::uint16_t ring;
  PCL_MAKE_ALIGNED_OPERATOR_NEW
} EIGEN_ALIGN16;
POINT_CLOUD_REGISTER_POINT_STRUCT(PointXYZIR,
                                  (float, x, x)(float, y, y)(float, z, z)(float, intensity, intensity)(
                                      std::uint16_t, ring, ring))

// Another driver's choices: double coordinates, an 8-bit intensity under the
// name "i", the ring as a float named "laser_id", and a timestamp to skip.
struct OddPoint {
  double timestamp;
  double x, y, z;
  std::uint8_t i;
  float laser_id;
};
POINT_CLOUD_REGISTER_POINT_STRUCT(OddPoint, (double, timestamp, timestamp)(double, x, x)(double, y, y)(
                                                double, z, z)(std::uint8_t, i, i)(float, laser_id, laser_id))

namespace l2s::adapters {
namespace {

const float kNaN = std::numeric_limits<float>::quiet_NaN();

pcl::PointCloud<PointXYZIR> velodyne_cloud(int n) {
  pcl::PointCloud<PointXYZIR> cloud;
  for (int i = 0; i < n; ++i) {
    PointXYZIR p;
    p.x = 1.0f + i;
    p.y = -0.5f * i;
    p.z = 0.25f;
    p.intensity = 10.0f * i;
    p.ring = static_cast<std::uint16_t>(15 - i % 16);
    cloud.push_back(p);
  }
  return cloud;
}

LidarCloud lidar_cloud(int n) {
  LidarCloud cloud;
  for (int i = 0; i < n; ++i) {
    cloud.points.emplace_back(0.5 * i, -0.25 * i, 1.0 + i);
    cloud.intensity.push_back(3.0f * i);
    cloud.ring.push_back(static_cast<std::uint16_t>(i % 32));
  }
  return cloud;
}

void expect_same(const LidarCloud& a, const LidarCloud& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i)
    for (int k = 0; k < 3; ++k)
      if (std::isnan(b.points[i][k]))
        EXPECT_TRUE(std::isnan(a.points[i][k])) << i;
      else
        EXPECT_EQ(a.points[i][k], b.points[i][k]) << "point " << i << " axis " << k;
  EXPECT_EQ(a.intensity, b.intensity);
  EXPECT_EQ(a.ring, b.ring);
}

TEST(PclAdapter, ConvertsXyzIntensityAndRing) {
  const LidarCloud converted = from_pcl(velodyne_cloud(5));
  ASSERT_EQ(converted.size(), 5u);
  ASSERT_TRUE(converted.has_ring());
  ASSERT_TRUE(converted.has_intensity());
  for (int i = 0; i < 5; ++i) {
    EXPECT_DOUBLE_EQ(converted.points[i].x(), 1.0 + i);
    EXPECT_DOUBLE_EQ(converted.points[i].y(), -0.5 * i);
    EXPECT_FLOAT_EQ(converted.intensity[i], 10.0f * i);
    EXPECT_EQ(converted.ring[i], 15 - i);
  }
}

TEST(PclAdapter, TypedAndGenericFormsAgree) {
  const auto typed = velodyne_cloud(40);
  pcl::PCLPointCloud2 generic;
  pcl::toPCLPointCloud2(typed, generic);
  expect_same(from_pcl(generic), from_pcl(typed));
}

TEST(PclAdapter, ReadsPaddedPointTypesAndKeepsNanPoints) {
  // pcl::PointXYZI: x y z in a 16-byte block, intensity in the next (32 bytes per point).
  pcl::PointCloud<pcl::PointXYZI> cloud;
  cloud.push_back(pcl::PointXYZI(7.0f));
  cloud.back().x = 1.0f;
  pcl::PointXYZI nan_point;
  nan_point.x = nan_point.y = nan_point.z = kNaN;
  cloud.push_back(nan_point);
  const LidarCloud converted = from_pcl(cloud);
  ASSERT_EQ(converted.size(), 2u);
  EXPECT_FALSE(converted.has_ring());
  EXPECT_EQ(converted.intensity, (std::vector<float>{7.0f, nan_point.intensity}));
  EXPECT_EQ(converted.points[0].x(), 1.0);
  EXPECT_TRUE(std::isnan(converted.points[1].x()));
}

TEST(PclAdapter, ReadsOtherNamesAndTypes) {
  pcl::PointCloud<OddPoint> cloud;
  cloud.push_back(OddPoint{123.0, 0.1, 0.2, 0.3, 250, 7.0f});
  const LidarCloud converted = from_pcl(cloud);
  ASSERT_EQ(converted.size(), 1u);
  EXPECT_EQ(converted.points[0], Eigen::Vector3d(0.1, 0.2, 0.3));  // doubles stay exact
  EXPECT_EQ(converted.intensity, std::vector<float>{250.0f});
  EXPECT_EQ(converted.ring, std::vector<std::uint16_t>{7});
}

TEST(PclAdapter, OrganisedCloudWithPaddedRowsComesOutRowByRow) {
  auto typed = velodyne_cloud(12);
  typed.width = 4;
  typed.height = 3;
  pcl::PCLPointCloud2 generic;
  pcl::toPCLPointCloud2(typed, generic);
  // Pad every row by 8 bytes, as a driver aligning rows might.
  const std::size_t row = generic.row_step, padded = row + 8;
  std::vector<std::uint8_t> data(padded * 3, 0xAB);
  for (std::size_t r = 0; r < 3; ++r) std::memcpy(&data[r * padded], &generic.data[r * row], row);
  generic.data = data;
  generic.row_step = static_cast<pcl::uindex_t>(padded);
  const LidarCloud converted = from_pcl(generic);
  ASSERT_EQ(converted.size(), 12u);
  for (int i = 0; i < 12; ++i) EXPECT_DOUBLE_EQ(converted.points[i].x(), 1.0 + i) << "row-major order";
  EXPECT_EQ(from_pcl(typed).points, converted.points);
}

TEST(PclAdapter, SwapsTheOtherByteOrder) {
  const auto typed = velodyne_cloud(8);
  pcl::PCLPointCloud2 generic;
  pcl::toPCLPointCloud2(typed, generic);
  const LidarCloud expected = from_pcl(generic);
  // The same cloud as a big-endian machine would hand it over.
  std::size_t swapped = 0;
  for (std::size_t p = 0; p < typed.size(); ++p)
    for (const auto& field : generic.fields) {
      const std::size_t size = field.datatype == pcl::PCLPointField::UINT16 ? 2 : 4;
      std::uint8_t* at = &generic.data[p * generic.point_step + field.offset];
      std::reverse(at, at + size);
      ++swapped;
    }
  ASSERT_EQ(swapped, 8u * 5u);
  generic.is_bigendian = !generic.is_bigendian;
  expect_same(from_pcl(generic), expected);
}

TEST(PclAdapter, RoundTripsThroughTypedClouds) {
  const LidarCloud cloud = lidar_cloud(50);
  const auto velodyne = to_pcl<PointXYZIR>(cloud);
  EXPECT_EQ(velodyne.width, 50u);
  EXPECT_EQ(velodyne.height, 1u);
  EXPECT_TRUE(velodyne.is_dense);
  expect_same(from_pcl(velodyne), cloud);  // every value is exact in float
  // A type without ring or intensity keeps what it can.
  const auto xyz = to_pcl<pcl::PointXYZ>(cloud);
  const LidarCloud back = from_pcl(xyz);
  EXPECT_EQ(back.points, cloud.points);
  EXPECT_FALSE(back.has_intensity());
  EXPECT_FALSE(back.has_ring());
}

TEST(PclAdapter, RoundTripsThroughPclPointCloud2AndPclsOwnConversions) {
  LidarCloud cloud = lidar_cloud(20);
  cloud.points[3] = Eigen::Vector3d::Constant(std::nan(""));
  const pcl::PCLPointCloud2 generic = to_pcl_cloud2(cloud);
  EXPECT_FALSE(generic.is_dense);
  EXPECT_EQ(generic.point_step % 4, 0u);
  expect_same(from_pcl(generic), cloud);
  pcl::PointCloud<PointXYZIR> typed;
  pcl::fromPCLPointCloud2(generic, typed);  // PCL reads what we wrote
  ASSERT_EQ(typed.size(), 20u);
  EXPECT_EQ(typed[5].ring, cloud.ring[5]);
  EXPECT_EQ(typed[5].intensity, cloud.intensity[5]);
  EXPECT_EQ(typed[5].z, static_cast<float>(cloud.points[5].z()));
}

TEST(PclAdapter, ConvertsToNarrowerTypesByRoundingAndClamping) {
  LidarCloud cloud;
  cloud.points = {Eigen::Vector3d(1, 2, 3), Eigen::Vector3d(4, 5, 6)};
  cloud.intensity = {300.4f, -2.0f};
  cloud.ring = {3, 4};
  const auto odd = to_pcl<OddPoint>(cloud);
  EXPECT_EQ(odd[0].i, 255);
  EXPECT_EQ(odd[1].i, 0);
  EXPECT_EQ(odd[1].laser_id, 4.0f);
  EXPECT_EQ(odd[1].x, 4.0);
}

TEST(PclAdapter, RejectsCloudsWithoutCoordinates) {
  pcl::PCLPointCloud2 no_xyz;
  no_xyz.width = 1;
  no_xyz.height = 1;
  EXPECT_THROW(from_pcl(no_xyz), InputError);
  try {
    from_pcl(pcl::PointCloud<pcl::Normal>());
    FAIL() << "a cloud without x y z must throw";
  } catch (const InputError& error) {
    EXPECT_STREQ(error.what(), "PCL cloud: no field x (x y z are required)");
  }
}

TEST(PclAdapter, RejectsDataShorterThanItsRows) {
  pcl::PCLPointCloud2 generic;
  pcl::toPCLPointCloud2(velodyne_cloud(10), generic);
  generic.data.resize(generic.data.size() - 1);
  EXPECT_THROW(from_pcl(generic), InputError);
  pcl::toPCLPointCloud2(velodyne_cloud(10), generic);
  generic.row_step = generic.point_step * 9;  // rows would overlap
  EXPECT_THROW(from_pcl(generic), InputError);
}

TEST(PclAdapter, RejectsFieldsOutsideThePointOrOfNoNumberType) {
  pcl::PCLPointCloud2 generic;
  pcl::toPCLPointCloud2(velodyne_cloud(2), generic);
  auto broken = generic;
  broken.fields[2].offset = broken.point_step - 2;  // z would read past its point
  EXPECT_THROW(from_pcl(broken), InputError);
  broken = generic;
  broken.fields[0].datatype = 42;
  EXPECT_THROW(from_pcl(broken), InputError);
}

TEST(PclAdapter, RejectsRingsThatAreNoLaserIndex) {
  pcl::PointCloud<OddPoint> cloud;
  cloud.push_back(OddPoint{0.0, 1.0, 2.0, 3.0, 0, -1.0f});
  EXPECT_THROW(from_pcl(cloud), InputError);
  cloud[0].laser_id = 2.5f;
  EXPECT_THROW(from_pcl(cloud), InputError);
}

TEST(PclAdapter, RejectsSweepsWhoseAttributesDisagreeWithThePoints) {
  LidarCloud cloud = lidar_cloud(4);
  cloud.intensity.pop_back();
  EXPECT_THROW(to_pcl_cloud2(cloud), InputError);
  EXPECT_THROW(to_pcl<PointXYZIR>(cloud), InputError);
}

}  // namespace
}  // namespace l2s::adapters
