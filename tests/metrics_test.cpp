#include <l2s/metrics.hpp>

#include <gtest/gtest.h>

#include <cmath>

namespace {

Eigen::Isometry3d pose(double yaw, double pitch, double roll, const Eigen::Vector3d& t) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  T.translation() = t;
  return T;
}

TEST(PoseError, IsZeroForIdenticalPoses) {
  const auto T = pose(0.3, -0.1, 0.2, {1, 2, 3});
  const auto error = l2s::pose_error(T, T);
  EXPECT_NEAR(error.translation, 0.0, 1e-12);
  EXPECT_NEAR(error.rotation, 0.0, 1e-9);
}

TEST(PoseError, MeasuresTranslationAsEuclideanDistance) {
  const auto error = l2s::pose_error(pose(0, 0, 0, {0.03, 0.04, 0}), pose(0, 0, 0, {0, 0, 0}));
  EXPECT_NEAR(error.translation, 0.05, 1e-12);
}

TEST(PoseError, MeasuresRotationAsAngleOfRelativeRotation) {
  // A rotation about any axis by a known angle, composed with a common base pose.
  const auto base = pose(0.5, 0.2, -0.3, {0, 0, 0});
  Eigen::Isometry3d other = base;
  other.linear() = base.linear() * Eigen::AngleAxisd(0.01, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  EXPECT_NEAR(l2s::pose_error(other, base).rotation, 0.01, 1e-9);
  // Tiny angles stay accurate (acos(trace) would lose them).
  other.linear() = base.linear() * Eigen::AngleAxisd(1e-7, Eigen::Vector3d::UnitY()).toRotationMatrix();
  EXPECT_NEAR(l2s::pose_error(other, base).rotation, 1e-7, 1e-12);
}

}  // namespace
