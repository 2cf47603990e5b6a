// The physical stereo rig against OpenCV's own camera functions: lens models
// (projectPoints, undistortPoints, fisheye), rectification rotations
// (stereoRectify), rectified rows lining up, and rectified images without an
// invalid border (initUndistortRectifyMap).

#include <l2s/sim/stereo_rig.hpp>

#include <l2s/error.hpp>

#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>

#include <cmath>
#include <ostream>
#include <cstdio>
#include <random>
#include <string>

namespace l2s::sim {
namespace {

constexpr double kDeg = 3.141592653589793 / 180.0;

struct RigCase {
  std::string name;
  int width, height;
  double hfov_deg, baseline;
  DistortionModel model;
};

void PrintTo(const RigCase& c, std::ostream* os) { *os << c.name; }

StereoRig make_rig(const RigCase& c) {
  StereoRig nominal;
  nominal.width = c.width;
  nominal.height = c.height;
  nominal.horizontal_fov = c.hfov_deg * kDeg;
  nominal.baseline = c.baseline;
  return nominal.with_real_lenses(c.model);
}

cv::Mat to_cv(const Eigen::MatrixXd& m) {
  cv::Mat out;
  cv::eigen2cv(m, out);
  return out;
}

cv::Mat distortion_of(const CameraInfo& info) {
  return cv::Mat(info.distortion_coefficients, true).reshape(1, 1);
}

std::string format_px(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", value);
  return text;
}

bool fisheye(const CameraInfo& info) { return info.distortion_model == "equidistant"; }

/// OpenCV's undistortion of raw pixels into the rectified image (R, P).
std::vector<cv::Point2d> cv_rectify_points(const std::vector<cv::Point2d>& raw, const CameraInfo& info) {
  std::vector<cv::Point2d> out;
  const cv::Mat K = to_cv(info.camera_matrix), R = to_cv(info.rectification_matrix),
                P = to_cv(info.projection_matrix);
  const cv::TermCriteria criteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 100, 1e-14);
  if (fisheye(info))
    cv::fisheye::undistortPoints(raw, out, K, distortion_of(info), R, P, criteria);
  else
    cv::undistortPoints(raw, out, K, distortion_of(info), R, P, criteria);
  return out;
}

class StereoRigCase : public ::testing::TestWithParam<RigCase> {};

TEST_P(StereoRigCase, LensModelMatchesOpenCvProjectPoints) {
  const StereoRig rig = make_rig(GetParam());
  const StereoCamera cams = rig.cameras();
  ASSERT_EQ(cams.images, GetParam().model == DistortionModel::None ? ImageKind::Rectified : ImageKind::Raw);
  if (cams.images != ImageKind::Raw) GTEST_SKIP() << "rectified images: no lens model to compare";
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> spread(-0.8, 0.8);
  for (int index = 0; index < 2; ++index) {
    const CameraInfo& info = index == 0 ? cams.left : cams.right;
    std::vector<cv::Point3d> points;
    std::vector<Eigen::Vector2d> ours;
    for (int i = 0; i < 200; ++i) {
      const Eigen::Vector3d p(spread(rng) * 3.0, spread(rng) * 2.0, 3.0);
      const Eigen::Vector2d px = rig.project_optical(index, p);
      if (!px.allFinite()) continue;
      points.emplace_back(p.x(), p.y(), p.z());
      ours.push_back(px);
    }
    ASSERT_GT(points.size(), 150u);
    std::vector<cv::Point2d> theirs;
    const cv::Mat zero = cv::Mat::zeros(3, 1, CV_64F);
    if (fisheye(info))
      cv::fisheye::projectPoints(points, theirs, zero, zero, to_cv(info.camera_matrix), distortion_of(info));
    else
      cv::projectPoints(points, zero, zero, to_cv(info.camera_matrix), distortion_of(info), theirs);
    for (std::size_t i = 0; i < ours.size(); ++i) {
      EXPECT_NEAR(ours[i].x(), theirs[i].x, 1e-6) << info.camera_name << " point " << i;
      EXPECT_NEAR(ours[i].y(), theirs[i].y, 1e-6) << info.camera_name << " point " << i;
    }
  }
}

TEST_P(StereoRigCase, UndistortionAgreesWithOpenCv) {
  const StereoRig rig = make_rig(GetParam());
  const StereoCamera cams = rig.cameras();
  if (cams.images != ImageKind::Raw) GTEST_SKIP();
  double worst = 0.0;
  for (int index = 0; index < 2; ++index) {
    const CameraInfo& info = index == 0 ? cams.left : cams.right;
    // Raw pixels over the whole image, corners included.
    std::vector<cv::Point2d> raw;
    for (int v = 0; v <= 16; ++v)
      for (int u = 0; u <= 16; ++u) raw.emplace_back(u * (rig.width - 1) / 16.0, v * (rig.height - 1) / 16.0);
    const std::vector<cv::Point2d> theirs = cv_rectify_points(raw, info);
    // Ours: the ray of the raw pixel, rectified by R, projected by P's pinhole.
    const Eigen::Matrix3d K_rect = info.projection_matrix.leftCols<3>();
    for (std::size_t i = 0; i < raw.size(); ++i) {
      const Eigen::Matrix3d K = info.camera_matrix;
      const Eigen::Vector2d distorted((raw[i].x - K(0, 2)) / K(0, 0), (raw[i].y - K(1, 2)) / K(1, 1));
      const Eigen::Vector2d n = rig.lenses[static_cast<std::size_t>(index)].distortion.undistort(distorted);
      const Eigen::Vector3d q = K_rect * (info.rectification_matrix * n.homogeneous());
      const Eigen::Vector2d ours = q.head<2>() / q.z();
      worst = std::max(worst, (ours - Eigen::Vector2d(theirs[i].x, theirs[i].y)).norm());
    }
  }
  RecordProperty("worst_px", format_px(worst));
  EXPECT_LT(worst, 0.1);
  EXPECT_LT(worst, 1e-3) << "both solve the same equations; they should agree far better than 0.1 px";
}

TEST_P(StereoRigCase, RectificationRotationsMatchStereoRectify) {
  const StereoRig rig = make_rig(GetParam());
  const StereoCamera cams = rig.cameras();
  // OpenCV's convention: p_right = R p_left + T.
  const Eigen::Isometry3d T_left_right =
      rig.T_cambody_optical(0).inverse() * rig.T_cambody_optical(1);
  const Eigen::Isometry3d T_right_left = T_left_right.inverse();
  cv::Mat R1, R2, P1, P2, Q;
  cv::stereoRectify(to_cv(cams.left.camera_matrix), cv::Mat(), to_cv(cams.right.camera_matrix), cv::Mat(),
                    cv::Size(rig.width, rig.height), to_cv(T_right_left.linear()),
                    to_cv(T_right_left.translation()), R1, R2, P1, P2, Q, cv::CALIB_ZERO_DISPARITY, 0);
  Eigen::Matrix3d R1e, R2e;
  cv::cv2eigen(R1, R1e);
  cv::cv2eigen(R2, R2e);
  EXPECT_LT((R1e - cams.left.rectification_matrix).norm(), 1e-9);
  EXPECT_LT((R2e - cams.right.rectification_matrix).norm(), 1e-9);
  EXPECT_NEAR(cams.baseline(), T_left_right.translation().norm(), 1e-12);
}

TEST_P(StereoRigCase, RectifiedRowsLineUp) {
  // A point seen by both raw cameras lands on the same rectified row after
  // OpenCV rectifies each image with its own K, D, R, P.
  const StereoRig rig = make_rig(GetParam());
  const StereoCamera cams = rig.cameras();
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> lateral(-1.5, 1.5), depth(1.2, 8.0);
  double worst = 0.0;
  int points = 0;
  for (int i = 0; i < 300; ++i) {
    const double x = depth(rng);
    const Eigen::Vector3d p_cambody(x, lateral(rng) * x / 3.0, lateral(rng) * x / 4.0);
    const Eigen::Vector2d left = rig.project(0, p_cambody), right = rig.project(1, p_cambody);
    if (!left.allFinite() || !right.allFinite()) continue;
    const auto inside = [&](const Eigen::Vector2d& px) {
      return px.x() >= 0 && px.y() >= 0 && px.x() <= rig.width - 1 && px.y() <= rig.height - 1;
    };
    if (!inside(left) || !inside(right)) continue;
    ++points;
    if (cams.images == ImageKind::Rectified) {
      worst = std::max(worst, std::abs(left.y() - right.y()));
      continue;
    }
    const cv::Point2d l = cv_rectify_points({{left.x(), left.y()}}, cams.left)[0];
    const cv::Point2d r = cv_rectify_points({{right.x(), right.y()}}, cams.right)[0];
    worst = std::max(worst, std::abs(l.y - r.y));
  }
  ASSERT_GT(points, 100);
  RecordProperty("worst_row_px", format_px(worst));
  EXPECT_LT(worst, 0.05);
}

TEST_P(StereoRigCase, RectifiedImagesHaveNoInvalidBorder) {
  const StereoRig rig = make_rig(GetParam());
  const StereoCamera cams = rig.cameras();
  for (const CameraInfo* info : {&cams.left, &cams.right}) {
    cv::Mat map_x, map_y;
    const cv::Size size(rig.width, rig.height);
    if (fisheye(*info))
      cv::fisheye::initUndistortRectifyMap(to_cv(info->camera_matrix), distortion_of(*info),
                                           to_cv(info->rectification_matrix), to_cv(info->projection_matrix),
                                           size, CV_32FC1, map_x, map_y);
    else
      cv::initUndistortRectifyMap(to_cv(info->camera_matrix), distortion_of(*info),
                                  to_cv(info->rectification_matrix), to_cv(info->projection_matrix),
                                  size, CV_32FC1, map_x, map_y);
    double lo_x, hi_x, lo_y, hi_y;
    cv::minMaxLoc(map_x, &lo_x, &hi_x);
    cv::minMaxLoc(map_y, &lo_y, &hi_y);
    // float maps: allow their rounding
    EXPECT_GE(lo_x, -1e-3) << info->camera_name;
    EXPECT_GE(lo_y, -1e-3) << info->camera_name;
    EXPECT_LE(hi_x, rig.width - 1 + 1e-3) << info->camera_name;
    EXPECT_LE(hi_y, rig.height - 1 + 1e-3) << info->camera_name;
    // ...and the window is not needlessly small: it reaches the raw border somewhere.
    EXPECT_LT(std::min({lo_x, lo_y, rig.width - 1 - hi_x, rig.height - 1 - hi_y}), 2.0) << info->camera_name;

    // The maps are OpenCV's rectified -> raw pixel model; ours must agree.
    const int index = info == &cams.left ? 0 : 1;
    const Eigen::Matrix3d back =
        info->rectification_matrix.transpose() * info->projection_matrix.leftCols<3>().inverse();
    double worst = 0.0;
    for (int v = 0; v < rig.height; v += 37)
      for (int u = 0; u < rig.width; u += 41) {
        const Eigen::Vector3d ray = back * Eigen::Vector3d(u, v, 1.0);
        const Eigen::Vector2d d =
            rig.lenses[static_cast<std::size_t>(index)].distortion.distort(ray.head<2>() / ray.z());
        const Eigen::Vector2d ours = (rig.camera_matrix(index) * d.homogeneous()).head<2>();
        worst = std::max(worst, (ours - Eigen::Vector2d(map_x.at<float>(v, u), map_y.at<float>(v, u))).norm());
      }
    EXPECT_LT(worst, 0.01) << info->camera_name;  // the maps are single precision
  }
}

INSTANTIATE_TEST_SUITE_P(
    Rigs, StereoRigCase,
    ::testing::Values(RigCase{"Bumblebee_plumb_bob", 1280, 960, 43.0, 0.12, DistortionModel::PlumbBob},
                      RigCase{"Wide_plumb_bob", 1920, 1200, 100.0, 0.3, DistortionModel::PlumbBob},
                      RigCase{"Vga_equidistant", 640, 480, 66.0, 0.07, DistortionModel::Equidistant},
                      RigCase{"Wide_equidistant", 1280, 960, 100.0, 0.5, DistortionModel::Equidistant},
                      RigCase{"Tilted_undistorted", 1280, 960, 66.0, 0.12, DistortionModel::None}),
    [](const auto& info) { return info.param.name; });

TEST(StereoRig, DefaultIsThePapersIdealRectifiedPair) {
  const StereoRig rig;
  EXPECT_TRUE(rig.ideal());
  const StereoCamera cams = rig.cameras();
  EXPECT_EQ(cams.images, ImageKind::Rectified);
  EXPECT_NEAR(cams.baseline(), 0.12, 1e-12);
  EXPECT_DOUBLE_EQ(cams.left.fx(), rig.fx());
  EXPECT_TRUE(rig.T_optical_camera().isApprox(Eigen::Isometry3d::Identity()));
  StereoRig raw = rig;
  raw.raw_images = true;
  EXPECT_EQ(raw.cameras().images, ImageKind::Raw);
}

TEST(StereoRig, RectifiedImagesOfATiltedPairUseTheRectifiedFrame) {
  StereoRig rig = StereoRig{}.with_real_lenses(DistortionModel::None);
  ASSERT_EQ(rig.images(), ImageKind::Rectified);
  const StereoCamera cams = rig.cameras();
  // The dataset's camera frame is the rectified left frame: p_rect = R_left * p_optical.
  const Eigen::Matrix3d R = rig.T_optical_camera().linear().transpose();
  EXPECT_LT((R - cams.left.rectification_matrix).norm(), 1e-12);
  const Eigen::Vector3d p_cambody(4.0, 0.5, -0.3);
  const Eigen::Vector3d p_optical = rig.T_cambody_optical(0).inverse() * p_cambody;
  const Eigen::Vector2d expected = cams.left.project(R * p_optical);  // P of left.yaml
  EXPECT_LT((rig.project(0, p_cambody) - expected).norm(), 1e-9);
  const Eigen::Vector2d expected_right = cams.right.project(R * p_optical);
  EXPECT_LT((rig.project(1, p_cambody) - expected_right).norm(), 1e-9);
}

TEST(StereoRig, ValidationNamesTheBadField) {
  StereoRig rig;
  rig.lenses[1].aspect = 1.2;
  try {
    rig.validate();
    FAIL() << "expected ParamError";
  } catch (const ParamError& e) {
    EXPECT_EQ(e.field(), "camera.right.aspect");
  }
  rig = StereoRig{};
  rig.horizontal_fov = 100 * kDeg;
  rig.lenses[0].distortion.model = DistortionModel::PlumbBob;
  rig.lenses[0].distortion.coefficients = {-0.6, 0.0, 0.0, 0.0, 0.0};  // folds inside the image
  try {
    rig.validate();
    FAIL() << "expected ParamError";
  } catch (const ParamError& e) {
    EXPECT_EQ(e.field(), "camera.left.distortion");
  }
  rig = StereoRig{};
  rig.right_rotation = Eigen::Vector3d(0.3, 0.0, 0.0);
  EXPECT_THROW(rig.validate(), ParamError);
}

TEST(StereoRig, ProjectIsNanWhereTheLensCannotImage) {
  StereoRig rig = StereoRig{}.with_real_lenses(DistortionModel::PlumbBob);
  EXPECT_FALSE(rig.project(0, Eigen::Vector3d(-2.0, 0.0, 0.0)).allFinite());  // behind
  rig.lenses[0].distortion.coefficients = {-0.3, 0.0, 0.0, 0.0, 0.0};  // folds at r = 1.05
  EXPECT_FALSE(rig.project_optical(0, Eigen::Vector3d(3.0, 0.0, 1.0)).allFinite());
  EXPECT_TRUE(rig.project_optical(0, Eigen::Vector3d(0.3, 0.0, 1.0)).allFinite());
}

}  // namespace
}  // namespace l2s::sim
