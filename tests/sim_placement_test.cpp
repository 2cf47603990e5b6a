// Board placements: the nine settings of Table I get a pose that passes the
// checker for all three lidar models, and bad poses are reported by name.

#include <l2s/sim/placement.hpp>

#include <gtest/gtest.h>

#include <cmath>

namespace l2s::sim {
namespace {

const std::vector<LidarModel>& all_models() {
  static const std::vector<LidarModel> models{LidarModel::vlp16(), LidarModel::hdl32(),
                                              LidarModel::hdl64()};
  return models;
}

struct PlacementCase {
  int setting;
  std::string board;
};

class PaperSettingPlacement : public ::testing::TestWithParam<PlacementCase> {};

TEST_P(PaperSettingPlacement, PassesForEveryLidarModel) {
  const Target target = Target::preset(GetParam().board);
  const SensorSetting setting = paper_setting(GetParam().setting);
  const PlacementResult result = find_placement(target, setting, all_models());
  ASSERT_TRUE(result.found);
  const Scene scene = make_scene(target, result.pose);
  for (const LidarModel& model : all_models()) {
    // Re-check independently of the search's own reports.
    const PlacementReport report = check_placement(scene, model, setting);
    EXPECT_TRUE(report.ok) << model.name << "\n" << report.summary();
    for (int h = 0; h < 4; ++h) EXPECT_GE(report.rings_per_hole[h], 2) << model.name << " hole " << h;
    EXPECT_GE(report.image_margin, 5.0);
    EXPECT_LE(report.normal_elevation_camera, 0.4);
    EXPECT_LE(report.normal_elevation_lidar, 0.4);
  }
  // Not axis-aligned, within 2-5.5 m, roughly vertical.
  EXPECT_GE(std::abs(result.pose.yaw), 0.1);
  EXPECT_GE(result.pose.x, 2.0);
  EXPECT_LE(result.pose.x, 5.5);
}

std::vector<PlacementCase> all_cases() {
  std::vector<PlacementCase> cases;
  for (int s = 1; s <= 9; ++s) cases.push_back({s, "default"});
  for (int s = 1; s <= 9; ++s) cases.push_back({s, "paper2017"});
  return cases;
}

INSTANTIATE_TEST_SUITE_P(TableI, PaperSettingPlacement, ::testing::ValuesIn(all_cases()),
                         [](const auto& info) {
                           return info.param.board + "_setting" + std::to_string(info.param.setting);
                         });

TEST(CheckPlacement, IsDeterministic) {
  const PlacementResult a = find_placement(Target{}, paper_setting(4), all_models());
  const PlacementResult b = find_placement(Target{}, paper_setting(4), all_models());
  EXPECT_EQ(a.pose.x, b.pose.x);
  EXPECT_EQ(a.pose.y, b.pose.y);
  EXPECT_EQ(a.pose.z, b.pose.z);
  EXPECT_EQ(a.pose.yaw, b.pose.yaw);
}

TEST(CheckPlacement, ReportsABoardOutsideTheImage) {
  // 1.5 m to the left at 3 m: the board leaves the left image.
  const Scene scene = make_scene(Target{}, BoardPose{3.0, 1.5, 0.0, 0.2, 0.0, 0.0});
  const PlacementReport report = check_placement(scene, LidarModel::vlp16(), paper_setting(7));
  EXPECT_FALSE(report.ok);
  EXPECT_LT(report.image_margin, 0.0);
  EXPECT_NE(report.summary().find("left image"), std::string::npos) << report.summary();
}

TEST(CheckPlacement, ReportsHolesMissedByTheRingsOfAFarBoard) {
  // At 12 m the VLP-16's 2 deg rings are 0.42 m apart: at most one ring per hole.
  const Scene scene = make_scene(Target{}, BoardPose{12.0, 0.0, 0.0, 0.2, 0.0, 0.0});
  const PlacementReport report = check_placement(scene, LidarModel::vlp16(), paper_setting(7));
  EXPECT_FALSE(report.ok);
  bool names_hole = false;
  for (const std::string& f : report.failures)
    names_hole = names_hole || (f.find("vlp16: hole") != std::string::npos && f.find("need 2") != std::string::npos);
  EXPECT_TRUE(names_hole) << report.summary();
}

TEST(CheckPlacement, ReportsATiltedBoard) {
  // Pitched 0.6 rad: beyond the calibrator's verticality limits.
  const Scene scene = make_scene(Target{}, BoardPose{3.0, 0.0, 0.0, 0.2, 0.6, 0.0});
  const PlacementReport report = check_placement(scene, LidarModel::hdl64(), paper_setting(7));
  EXPECT_FALSE(report.ok);
  EXPECT_NE(report.summary().find("from horizontal"), std::string::npos) << report.summary();
}

TEST(CheckPlacement, OcclusionByClutterIsCaught) {
  // A box straight between the camera and the board.
  SceneLayout layout;
  Box box;
  box.T_cambody_box.translation() = Eigen::Vector3d(1.5, 0.0, 0.0);
  box.half_size = Eigen::Vector3d(0.1, 0.2, 0.2);
  layout.extra_clutter.push_back(box);
  const Scene scene = make_scene(Target{}, BoardPose{3.0, 0.0, 0.0, 0.2, 0.0, 0.0}, layout);
  const PlacementReport report = check_placement(scene, LidarModel::vlp16(), paper_setting(7));
  EXPECT_FALSE(report.ok);
  EXPECT_NE(report.summary().find("occluded"), std::string::npos) << report.summary();
}

}  // namespace
}  // namespace l2s::sim
