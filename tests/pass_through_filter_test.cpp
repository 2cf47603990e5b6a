#include <l2s/error.hpp>
#include <l2s/pass_through_filter.hpp>

#include <gtest/gtest.h>

#include <cmath>

namespace l2s {
namespace {

TEST(PassThroughFilter, KeepsPointsInsideBoxAndRange) {
  PassThroughFilter::Params params;
  params.min_xyz = Eigen::Vector3d(0.0, -2.0, -1.0);
  params.max_xyz = Eigen::Vector3d(10.0, 2.0, 1.0);
  params.min_range = 1.0;
  params.max_range = 8.0;
  const std::vector<Eigen::Vector3d> points{
      {5.0, 0.0, 0.0},    // kept
      {-1.0, 0.0, 0.0},   // behind: box
      {5.0, 3.0, 0.0},    // left of the box
      {0.5, 0.0, 0.0},    // too close
      {9.0, 0.0, 0.0},    // too far
      {2.0, -1.9, 0.9}};  // kept
  const auto result = PassThroughFilter(params).filter(points);
  EXPECT_EQ(result.kept, (std::vector<std::size_t>{0, 5}));
  EXPECT_EQ(result.dropped_box, 2u);
  EXPECT_EQ(result.dropped_range, 2u);
  EXPECT_EQ(result.dropped_non_finite, 0u);
}

TEST(PassThroughFilter, DropsNonFinitePoints) {
  const double nan = std::nan("");
  const std::vector<Eigen::Vector3d> points{
      {1.0, 2.0, 3.0}, {nan, 0.0, 0.0}, {0.0, INFINITY, 0.0}, {4.0, 5.0, 6.0}};
  const auto result = PassThroughFilter().filter(points);  // defaults: everything finite passes
  EXPECT_EQ(result.kept, (std::vector<std::size_t>{0, 3}));
  EXPECT_EQ(result.dropped_non_finite, 2u);
}

TEST(PassThroughFilter, RejectsInvertedBoxNamingTheField) {
  PassThroughFilter::Params params;
  params.min_xyz.y() = 1.0;
  params.max_xyz.y() = -1.0;
  try {
    PassThroughFilter filter(params);
    FAIL() << "expected ParamError";
  } catch (const ParamError& e) {
    EXPECT_EQ(e.field(), "max_xyz.y");
  }
  PassThroughFilter::Params range;
  range.max_range = 0.0;
  EXPECT_THROW(PassThroughFilter{range}, ParamError);
}

TEST(PassThroughFilter, SelectKeepsRingAndIntensity) {
  LidarCloud cloud;
  cloud.points = {{1, 0, 0}, {2, 0, 0}, {3, 0, 0}};
  cloud.ring = {4, 5, 6};
  cloud.intensity = {0.1f, 0.2f, 0.3f};
  const LidarCloud out = select(cloud, {2, 0});
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out.points[0].x(), 3.0);
  EXPECT_EQ(out.ring, (std::vector<std::uint16_t>{6, 4}));
  EXPECT_EQ(out.intensity, (std::vector<float>{0.3f, 0.1f}));
}

}  // namespace
}  // namespace l2s
