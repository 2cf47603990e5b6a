#include <l2s/metrics.hpp>

#include <l2s/pose.hpp>

#include <gtest/gtest.h>

#include <cmath>

namespace {

TEST(PoseError, IsZeroForIdenticalPoses) {
  const auto T = l2s::pose_from_roll_pitch_yaw(0.2, -0.1, 0.3, {1, 2, 3});
  const auto error = l2s::pose_error(T, T);
  EXPECT_NEAR(error.translation, 0.0, 1e-12);
  EXPECT_NEAR(error.rotation, 0.0, 1e-9);
}

TEST(PoseError, MeasuresTranslationAsEuclideanDistance) {
  const auto error =
      l2s::pose_error(l2s::pose_from_roll_pitch_yaw(0, 0, 0, {0.03, 0.04, 0}), l2s::pose_from_roll_pitch_yaw(0, 0, 0, {0, 0, 0}));
  EXPECT_NEAR(error.translation, 0.05, 1e-12);
}

TEST(PoseError, MeasuresRotationAsAngleOfRelativeRotation) {
  // A rotation about any axis by a known angle, composed with a common base pose.
  const auto base = l2s::pose_from_roll_pitch_yaw(-0.3, 0.2, 0.5, {0, 0, 0});
  Eigen::Isometry3d other = base;
  other.linear() = base.linear() * Eigen::AngleAxisd(0.01, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  EXPECT_NEAR(l2s::pose_error(other, base).rotation, 0.01, 1e-9);
  // Tiny angles stay accurate (acos(trace) would lose them).
  other.linear() = base.linear() * Eigen::AngleAxisd(1e-7, Eigen::Vector3d::UnitY()).toRotationMatrix();
  EXPECT_NEAR(l2s::pose_error(other, base).rotation, 1e-7, 1e-12);
}

}  // namespace

namespace {

TEST(RollPitchYaw, InvertsPoseFromYpr) {
  const auto T = l2s::pose_from_roll_pitch_yaw(0.075, 0.258, -0.672, {0, 0, 0});
  const Eigen::Vector3d rpy = l2s::roll_pitch_yaw(T.rotation());
  EXPECT_NEAR(rpy[0], 0.075, 1e-12);
  EXPECT_NEAR(rpy[1], 0.258, 1e-12);
  EXPECT_NEAR(rpy[2], -0.672, 1e-12);
}

}  // namespace
