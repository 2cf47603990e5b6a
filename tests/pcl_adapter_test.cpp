#include <l2s/adapters/pcl.hpp>

#include <gtest/gtest.h>
#include <pcl/point_types.h>

#include <cmath>
#include <limits>

// A driver-style point with a ring, as Velodyne ROS drivers register it.
struct PointXYZIR {
  PCL_ADD_POINT4D;
  float intensity;
  std::uint16_t ring;
  PCL_MAKE_ALIGNED_OPERATOR_NEW
} EIGEN_ALIGN16;
POINT_CLOUD_REGISTER_POINT_STRUCT(PointXYZIR,
                                  (float, x, x)(float, y, y)(float, z, z)(float, intensity, intensity)(std::uint16_t, ring, ring))

namespace {

TEST(PclAdapter, ConvertsXyzIntensityAndRing) {
  pcl::PointCloud<PointXYZIR> cloud;
  for (int i = 0; i < 5; ++i) {
    PointXYZIR p;
    p.x = 1.0f + i;
    p.y = -0.5f * i;
    p.z = 0.25f;
    p.intensity = 10.0f * i;
    p.ring = static_cast<std::uint16_t>(15 - i);
    cloud.push_back(p);
  }
  const l2s::LidarCloud converted = l2s::adapters::from_pcl(cloud);
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

TEST(PclAdapter, KeepsNanPointsAndLeavesRingEmptyWhenAbsent) {
  pcl::PointCloud<pcl::PointXYZ> cloud;
  cloud.push_back(pcl::PointXYZ(1, 2, 3));
  const float nan = std::numeric_limits<float>::quiet_NaN();
  cloud.push_back(pcl::PointXYZ(nan, nan, nan));
  const auto converted = l2s::adapters::from_pcl(cloud);
  ASSERT_EQ(converted.size(), 2u);
  EXPECT_FALSE(converted.has_ring());
  EXPECT_FALSE(converted.has_intensity());
  EXPECT_TRUE(std::isnan(converted.points[1].x()));
}

TEST(PclAdapter, RejectsCloudsWithoutCoordinates) {
  pcl::PCLPointCloud2 no_xyz;
  no_xyz.width = 1;
  no_xyz.height = 1;
  EXPECT_THROW(l2s::adapters::from_pcl(no_xyz), l2s::Error);
}

}  // namespace
