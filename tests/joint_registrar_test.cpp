#include <l2s/joint_registrar.hpp>

#include <l2s/error.hpp>
#include <l2s/metrics.hpp>
#include <l2s/pose.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>

namespace l2s {
namespace {

const Eigen::Isometry3d& truth() {
  static const Eigen::Isometry3d T = pose_from_roll_pitch_yaw(-1.52, 0.03, -1.63, {-0.4, 0.12, -0.25});
  return T;
}

/// A board of the default pattern centred at `c` in the lidar frame, turned by `yaw`.
PosePair board(const Eigen::Vector3d& c, double yaw, std::mt19937& rng, double sigma) {
  std::normal_distribution<double> n(0.0, sigma);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const double ys[4] = {0.25, -0.25, 0.25, -0.25}, zs[4] = {0.2, 0.2, -0.2, -0.2};
  PosePair out;
  for (int h = 0; h < 4; ++h) {
    const Eigen::Vector3d p = c + R * Eigen::Vector3d(0.0, ys[h], zs[h]);
    out.target[h] = p + Eigen::Vector3d(n(rng), n(rng), n(rng));
    out.source[h] = truth().inverse() * p + Eigen::Vector3d(n(rng), n(rng), n(rng));
  }
  return out;
}

/// |estimate - truth| per DoF (tx ty tz roll pitch yaw).
std::array<double, 6> dof_errors(const Eigen::Isometry3d& T) {
  const Eigen::Vector3d dt = T.translation() - truth().translation();
  const Eigen::Vector3d dr = roll_pitch_yaw(T.rotation()) - roll_pitch_yaw(truth().rotation());
  std::array<double, 6> out{};
  for (int k = 0; k < 3; ++k) out[k] = std::abs(dt[k]), out[3 + k] = std::abs(std::remainder(dr[k], 2.0 * M_PI));
  return out;
}

/// Three poses spread over the view: left and near, right and far, low in the middle.
std::vector<PosePair> three_poses(std::mt19937& rng, double sigma) {
  return {board({3.0, 0.1, 0.0}, 0.3, rng, sigma), board({2.5, 1.0, 0.2}, -0.3, rng, sigma),
          board({4.5, -1.2, -0.4}, 0.2, rng, sigma)};
}

TEST(JointRegistrar, OnePoseIsRegistrarsResult) {
  std::mt19937 rng(1);
  const PosePair pose = board({3.0, 0.2, 0.1}, 0.3, rng, 0.003);
  const JointRegistrar::Result joint = JointRegistrar().estimate({pose});
  const Registrar::Result single = Registrar().estimate(pose.target, pose.source);
  ASSERT_TRUE(joint.found) << joint.reason;
  EXPECT_TRUE(joint.T_target_source.matrix() == single.T_lidar_camera.matrix());
  EXPECT_EQ(joint.single.translation_only, single.translation_only);
  EXPECT_TRUE(joint.leave_one_out.empty());
  EXPECT_TRUE(joint.uncertainty.valid) << joint.uncertainty.reason;
}

TEST(JointRegistrar, ThreePosesBeatOneOnTheSameData) {
  std::mt19937 rng(2);
  std::vector<double> one_r, three_r, one_t, three_t;
  for (int run = 0; run < 60; ++run) {
    const std::vector<PosePair> poses = three_poses(rng, 0.003);
    const auto e1 = pose_error(JointRegistrar().estimate({poses[0]}).T_target_source, truth());
    const auto e3 = pose_error(JointRegistrar().estimate(poses).T_target_source, truth());
    one_r.push_back(e1.rotation), three_r.push_back(e3.rotation);
    one_t.push_back(e1.translation), three_t.push_back(e3.translation);
  }
  const auto median = [](std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
  };
  EXPECT_LT(median(three_r), 0.5 * median(one_r));
  EXPECT_LT(median(three_t), 0.5 * median(one_t));
}

TEST(JointRegistrar, RejectsAnOutlyingPose) {
  std::mt19937 rng(3);
  std::vector<PosePair> poses = three_poses(rng, 0.002);
  poses.push_back(board({3.5, 0.5, 0.3}, -0.1, rng, 0.002));
  for (auto& p : poses[1].source) p += Eigen::Vector3d(0.05, -0.03, 0.04);  // a bad pose: centres 7 cm off
  const JointRegistrar::Result result = JointRegistrar().estimate(poses);
  ASSERT_TRUE(result.found) << result.reason;
  EXPECT_EQ(result.used, (std::vector<bool>{true, false, true, true}));
  ASSERT_EQ(result.notes.size(), 1u);
  EXPECT_NE(result.notes[0].find("pose 1 rejected"), std::string::npos) << result.notes[0];
  EXPECT_GT(result.pose_rms[1], 0.03);
  // The result is the fit of the good poses; keeping the bad one is far worse.
  const JointRegistrar::Result good = JointRegistrar().estimate({poses[0], poses[2], poses[3]});
  EXPECT_TRUE(result.T_target_source.isApprox(good.T_target_source, 1e-12));
  JointRegistrar::Params keep_all;
  keep_all.outlier_ratio = 1e9;
  const PoseError e = pose_error(result.T_target_source, truth());
  const PoseError all = pose_error(JointRegistrar(keep_all).estimate(poses).T_target_source, truth());
  EXPECT_LT(e.translation, all.translation / 2.0);
  EXPECT_EQ(result.leave_one_out.size(), 3u);
}

TEST(JointRegistrar, KeepsAllGoodPoses) {
  std::mt19937 rng(4);
  for (int run = 0; run < 30; ++run) {
    const JointRegistrar::Result result = JointRegistrar().estimate(three_poses(rng, 0.004));
    ASSERT_TRUE(result.found);
    EXPECT_EQ(result.used_count(), 3) << run << (result.notes.empty() ? "" : result.notes[0]);
  }
}

TEST(JointRegistrar, UncertaintyCoversTheTrueError) {
  // Isotropic noise on both sides, the model the covariance assumes: each
  // DoF's 95 % interval must hold the true value in about 95 % of runs.
  std::mt19937 rng(5);
  const int runs = 300;
  std::array<int, 6> covered{};
  JointRegistrar::Params noise_only;  // no error shared by a pose's centres here
  noise_only.pose_bias_translation = noise_only.pose_bias_rotation = 0.0;
  for (int run = 0; run < runs; ++run) {
    const std::vector<PosePair> poses = {board({3.0, 0.1, 0.0}, 0.3, rng, 0.003),
                                         board({4.0, -0.8, 0.2}, -0.2, rng, 0.003)};
    const JointRegistrar::Result result = JointRegistrar(noise_only).estimate(poses);
    ASSERT_TRUE(result.uncertainty.valid);
    const std::array<double, 6> error = dof_errors(result.T_target_source);
    for (int k = 0; k < 6; ++k) covered[k] += error[k] <= result.uncertainty.bound_95[k];
  }
  for (int k = 0; k < 6; ++k) {
    EXPECT_GE(covered[k], 0.9 * runs) << dof_names()[k];
    EXPECT_LE(covered[k], 0.99 * runs) << dof_names()[k];  // not vacuously wide
  }
}

TEST(JointRegistrar, JackknifeOverPosesCoversErrorsAPoseShares) {
  // Each pose's camera centres share an offset (a depth bias of that pose's
  // detection): no residual shows it, the spread over poses does.
  std::mt19937 rng(8);
  std::normal_distribution<double> bias(0.0, 0.003);
  const int runs = 200;
  int covered = 0, covered_by_residuals = 0;
  for (int run = 0; run < runs; ++run) {
    std::vector<PosePair> poses = three_poses(rng, 0.0005);
    poses.push_back(board({3.5, 0.5, 0.3}, -0.1, rng, 0.0005));
    poses.push_back(board({4.0, -0.4, -0.2}, 0.25, rng, 0.0005));
    for (auto& pose : poses) {
      const Eigen::Vector3d offset(bias(rng), bias(rng), bias(rng));
      for (auto& p : pose.source) p += offset;
    }
    JointRegistrar::Params keep_all;  // offsets this large relative to the noise may look like an outlier
    keep_all.outlier_ratio = 1e9;
    keep_all.pose_bias_translation = keep_all.pose_bias_rotation = 0.0;  // the jackknife alone
    const JointRegistrar::Result result = JointRegistrar(keep_all).estimate(poses);
    ASSERT_EQ(result.used_count(), 5);
    const FitUncertainty& u = result.uncertainty;
    const std::array<double, 6> error = dof_errors(result.T_target_source);
    for (int k = 0; k < 6; ++k) {
      covered += error[k] <= u.bound_95[k];
      covered_by_residuals += error[k] <= student_t_95(u.dof) * std::sqrt(u.covariance(k, k));
    }
  }
  EXPECT_GE(covered, 0.9 * 6 * runs);
  EXPECT_LT(covered_by_residuals, 0.8 * 6 * runs);  // the residuals alone would not
}

/// The pose's centres in the camera frame moved by a rigid motion about their
/// centroid: a depth or tilt bias of that pose's detection.
void move_rigidly(PosePair& pose, const Eigen::Vector3d& shift, const Eigen::Vector3d& turn) {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (const auto& p : pose.source) c += p / 4.0;
  const Eigen::Matrix3d R = Eigen::AngleAxisd(turn.norm(), turn.normalized()).toRotationMatrix();
  for (auto& p : pose.source) p = c + shift + R * (p - c);
}

TEST(JointRegistrar, ErrorsAPoseSharesAreCoveredWithOneOrTwoPoses) {
  // With one or two poses there is no jackknife; the shared error the
  // params describe (here exactly the one drawn) must be in the bound.
  const JointRegistrar::Params params;
  std::normal_distribution<double> shift(0.0, params.pose_bias_translation), turn(0.0, params.pose_bias_rotation);
  for (int poses_count : {1, 2}) {
    std::mt19937 rng(20 + poses_count);
    const int runs = 300;
    int covered = 0, covered_by_residuals = 0;
    for (int run = 0; run < runs; ++run) {
      // Centres averaged over many frames: little noise, the shared error dominates.
      std::vector<PosePair> poses = {board({3.0, 0.1, 0.0}, 0.3, rng, 0.0001)};
      if (poses_count == 2) poses.push_back(board({4.0, -0.8, 0.2}, -0.2, rng, 0.0001));
      for (auto& pose : poses)
        move_rigidly(pose, {shift(rng), shift(rng), shift(rng)}, {turn(rng), turn(rng), turn(rng)});
      const JointRegistrar::Result result = JointRegistrar(params).estimate(poses);
      ASSERT_TRUE(result.uncertainty.valid);
      const FitUncertainty& u = result.uncertainty;
      const std::array<double, 6> error = dof_errors(result.T_target_source);
      for (int k = 0; k < 6; ++k) {
        covered += error[k] <= u.bound_95[k];
        const double residual_sigma = std::sqrt(u.sigma[k] * u.sigma[k] - u.sigma_shared[k] * u.sigma_shared[k]);
        covered_by_residuals += error[k] <= student_t_95(u.dof) * residual_sigma;
      }
    }
    EXPECT_GE(covered, 0.92 * 6 * runs) << poses_count << " pose(s)";
    EXPECT_LE(covered, 0.99 * 6 * runs) << poses_count << " pose(s): not vacuously wide";
    EXPECT_LT(covered_by_residuals, 0.8 * 6 * runs) << poses_count << " pose(s): the residuals alone would not";
  }
}

TEST(JointRegistrar, SuggestsAPoseOnlyWhenPoorlyConditioned) {
  std::mt19937 rng(6);
  const JointRegistrar::Result one = JointRegistrar().estimate({board({4.0, 0.0, 0.0}, 0.0, rng, 0.002)});
  ASSERT_TRUE(one.uncertainty.valid);
  EXPECT_GT(one.uncertainty.condition, JointRegistrar::Params().max_condition);
  EXPECT_FALSE(one.uncertainty.suggestion.empty());
  EXPECT_FALSE(one.uncertainty.weakest_summary.empty());
  const JointRegistrar::Result three = JointRegistrar().estimate(three_poses(rng, 0.002));
  EXPECT_LT(three.uncertainty.condition, one.uncertainty.condition);
}

TEST(JointRegistrar, LeaveOnePoseOutMovesLittleOnConsistentPoses) {
  std::mt19937 rng(7);
  const JointRegistrar::Result result = JointRegistrar().estimate(three_poses(rng, 0.002));
  ASSERT_EQ(result.leave_one_out.size(), 3u);
  for (const auto& loo : result.leave_one_out) {
    EXPECT_TRUE(loo.found);
    EXPECT_LT(loo.translation, 0.03);
    EXPECT_GT(loo.translation, 0.0);
  }
}

TEST(JointRegistrar, ValidatesParams) {
  JointRegistrar::Params p;
  p.outlier_ratio = 1.0;
  EXPECT_THROW(JointRegistrar{p}, ParamError);
  p = {};
  p.min_poses_to_reject = 2;
  EXPECT_THROW(JointRegistrar{p}, ParamError);
  p = {};
  p.pose_bias_rotation = -0.001;
  EXPECT_THROW(JointRegistrar{p}, ParamError);
  EXPECT_FALSE(JointRegistrar().estimate({}).found);
}

}  // namespace
}  // namespace l2s
