// The rims' brightness steps summed along arcs (verify/rim_steps): a step of
// a few gray levels, below the noise per pixel, shows on the rims and not on
// the face around them; no step shows nowhere.

#include "verify/rim_steps.hpp"

#include <gtest/gtest.h>

#include <random>

namespace l2s::detail {
namespace {

constexpr double kFx = 600.0, kBaseline = 0.12, kRange = 2.5;

StereoCamera rig() {
  return {CameraInfo::ideal("left", 640, 480, kFx, 320.0, 240.0),
          CameraInfo::ideal("right", 640, 480, kFx, 320.0, 240.0, kBaseline), ImageKind::Rectified};
}

/// The board kRange ahead, facing the cameras (board x right, y up).
Eigen::Isometry3d board_ahead() {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::Vector3d(1.0, -1.0, -1.0).asDiagonal();
  T.translation() = Eigen::Vector3d(0.0, 0.0, kRange);
  return T;
}

/// One view of the board: its face `face` gray levels, what the holes (and
/// the surroundings) show `behind`, Gaussian noise of `noise`.
cv::Mat render(const Target& target, double face, double behind, double noise, double eye_x, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> gauss(0.0, noise);
  const auto holes = target.hole_centers();
  cv::Mat image(480, 640, CV_8UC1);
  for (int v = 0; v < image.rows; ++v)
    for (int u = 0; u < image.cols; ++u) {
      // The ray from the eye through the pixel meets the board plane at z = kRange.
      const Eigen::Vector2d q(eye_x + (u - 320.0) / kFx * kRange, -(v - 240.0) / kFx * kRange);
      bool on_face = std::abs(q.x()) < 0.5 * target.board_width && std::abs(q.y()) < 0.5 * target.board_height;
      for (const Eigen::Vector2d& c : holes) on_face = on_face && (q - c).norm() > target.hole_radius;
      image.at<std::uint8_t>(v, u) = cv::saturate_cast<std::uint8_t>((on_face ? face : behind) + gauss(rng));
    }
  return image;
}

RimSteps steps_for(double face, double behind) {
  const Target target;
  const cv::Mat left = render(target, face, behind, 2.0, 0.0, 1);
  const cv::Mat right = render(target, face, behind, 2.0, kBaseline, 2);
  return rim_steps(left, right, rig(), target, board_ahead());
}

TEST(RimSteps, AFaintStepBelowTheNoiseShowsOnTheRimsAndNotOnTheFace) {
  const RimSteps steps = steps_for(104.0, 100.0);  // 4 gray levels, noise sigma 2
  EXPECT_GT(steps.rims, 0.9);
  EXPECT_LT(steps.face, 0.1);
}

TEST(RimSteps, NoStepShowsNowhere) {
  const RimSteps steps = steps_for(100.0, 100.0);
  EXPECT_LT(steps.rims, 0.1);
  EXPECT_LT(steps.face, 0.1);
}

TEST(RimSteps, ABoardOutOfViewGivesNoShare) {
  const Target target;
  const cv::Mat image = render(target, 104.0, 100.0, 2.0, 0.0, 1);
  Eigen::Isometry3d behind = board_ahead();
  behind.translation().z() = -kRange;
  const RimSteps steps = rim_steps(image, image, rig(), target, behind);
  EXPECT_TRUE(std::isnan(steps.rims));
  EXPECT_TRUE(std::isnan(steps.face));
}

}  // namespace
}  // namespace l2s::detail
