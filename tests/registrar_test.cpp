#include <l2s/registrar.hpp>

#include <l2s/error.hpp>
#include <l2s/pose.hpp>

#include "support/test_data.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace l2s {
namespace {

/// Hole centres of the default board 3 m in front of the camera (optical frame).
HoleCenters camera_centres() {
  return {Eigen::Vector3d(-0.25, -0.2, 3.0), Eigen::Vector3d(0.25, -0.2, 3.05),
          Eigen::Vector3d(-0.25, 0.2, 2.98), Eigen::Vector3d(0.25, 0.2, 3.02)};
}

HoleCenters transformed(const Eigen::Isometry3d& T, const HoleCenters& in) {
  HoleCenters out;
  for (int i = 0; i < 4; ++i) out[i] = T * in[i];
  return out;
}

TEST(Registrar, RecoversKnownTransformExactly) {
  // Camera optical to lidar (x fwd, y left, z up) plus a large yaw and pitch.
  const Eigen::Isometry3d T_true = l2s::pose_from_roll_pitch_yaw(-0.1, 0.3, 0.67, {-0.4, 0.3, -0.2});
  const HoleCenters camera = camera_centres();
  const Registrar::Result result = Registrar().estimate(transformed(T_true, camera), camera);
  ASSERT_TRUE(result.found) << result.reason;
  EXPECT_POSE_NEAR(result.T_lidar_camera, T_true, 1e-6, 1e-9);
  EXPECT_LT(result.rms, 1e-9);
}

TEST(Registrar, RecoversKnownTransformFromNoisyCentres) {
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0.0, 0.003);
  const Eigen::Matrix3d optical_to_body = (Eigen::Matrix3d() << 0, 0, 1, -1, 0, 0, 0, -1, 0).finished();
  for (const double yaw : {0.0, 0.67, -1.2, 3.0}) {
    Eigen::Isometry3d T_true = l2s::pose_from_roll_pitch_yaw(0.05, 0.3, yaw, {0.1, -0.5, 0.8});
    T_true.linear() = T_true.linear() * optical_to_body;
    const HoleCenters camera = camera_centres();
    HoleCenters lidar = transformed(T_true, camera);
    for (auto& p : lidar) p += Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
    const Registrar::Result result = Registrar().estimate(lidar, camera);
    ASSERT_TRUE(result.found) << result.reason;
    // 3 mm noise on a 0.5 x 0.4 m pattern tilts the fit by ~0.5 deg, which the
    // 3 m lever to the camera origin turns into a few cm of translation; the
    // pattern's own centre is pinned down to the noise of the mean (~2 mm).
    EXPECT_POSE_NEAR(result.T_lidar_camera, T_true, 1.5, 0.08) << "yaw " << yaw;
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (const auto& p : camera) centre += p / 4.0;
    EXPECT_LT((result.T_lidar_camera * centre - T_true * centre).norm(), 0.006) << "yaw " << yaw;
    EXPECT_GT(result.rms, 0.0);
    EXPECT_LT(result.rms, 0.01);
  }
}

TEST(Registrar, TranslationStepIsMeanDifferenceWithoutRotation) {
  const HoleCenters camera = camera_centres();
  HoleCenters lidar;
  const std::array<Eigen::Vector3d, 4> jitter = {Eigen::Vector3d(0.01, 0, 0), Eigen::Vector3d(0, -0.02, 0),
                                                 Eigen::Vector3d(0, 0, 0.005), Eigen::Vector3d(-0.004, 0.003, 0)};
  const Eigen::Vector3d t(0.3, -0.1, 0.25);
  Eigen::Vector3d mean_difference = Eigen::Vector3d::Zero();
  for (int i = 0; i < 4; ++i) {
    lidar[i] = camera[i] + t + jitter[i];
    mean_difference += (lidar[i] - camera[i]) / 4.0;
  }
  const Registrar::Result result = Registrar().estimate(lidar, camera);
  ASSERT_TRUE(result.found) << result.reason;
  EXPECT_TRUE(result.translation_only.isApprox(mean_difference, 1e-12));
  // The full fit can only lower the residual of the pure translation.
  double translation_sq = 0.0;
  for (int i = 0; i < 4; ++i) translation_sq += (lidar[i] - camera[i] - result.translation_only).squaredNorm();
  EXPECT_LE(result.rms, std::sqrt(translation_sq / 4.0) + 1e-12);
}

TEST(Registrar, ReportsDegenerateInputInsteadOfThrowing) {
  const HoleCenters good = camera_centres();
  HoleCenters with_nan = good;
  with_nan[2].x() = std::numeric_limits<double>::quiet_NaN();
  HoleCenters coincident;
  coincident.fill(Eigen::Vector3d(1, 2, 3));
  HoleCenters collinear;
  for (int i = 0; i < 4; ++i) collinear[i] = Eigen::Vector3d(0.1 * i, 0.0, 3.0);

  const Registrar registrar;
  Registrar::Result result = registrar.estimate(with_nan, good);
  EXPECT_FALSE(result.found);
  EXPECT_NE(result.reason.find("NaN"), std::string::npos) << result.reason;
  result = registrar.estimate(good, coincident);
  EXPECT_FALSE(result.found);
  EXPECT_NE(result.reason.find("coincide"), std::string::npos) << result.reason;
  result = registrar.estimate(collinear, good);
  EXPECT_FALSE(result.found);
  EXPECT_NE(result.reason.find("collinear"), std::string::npos) << result.reason;
}

TEST(Registrar, RejectsInvalidParams) {
  Registrar::Params params;
  params.min_planarity = 1.5;
  try {
    Registrar{params};
    FAIL() << "expected ParamError";
  } catch (const ParamError& error) {
    EXPECT_EQ(error.field(), "min_planarity");
  }
}

}  // namespace
}  // namespace l2s
