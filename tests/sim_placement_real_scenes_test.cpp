// Placements for the lidars and scenes of real recordings: ring-free lidars
// need returns through and around each hole within the accumulation time;
// stands, side walls, low clutter and pillars must not break the search, and
// a failing placement still says why.

#include <l2s/sim/lidar_quirks.hpp>
#include <l2s/sim/placement.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace l2s::sim {
namespace {

/// Whether one failure line holds `text` (and `also`, when given).
bool mentions(const PlacementReport& report, const std::string& text, const std::string& also = "") {
  for (const std::string& f : report.failures)
    if (f.find(text) != std::string::npos && f.find(also) != std::string::npos) return true;
  return false;
}

struct RosetteCase {
  std::string model;
  int setting;
};

void PrintTo(const RosetteCase& c, std::ostream* os) { *os << c.model << " setting " << c.setting; }

class RosettePlacement : public ::testing::TestWithParam<RosetteCase> {};

TEST_P(RosettePlacement, FindsABoardWithReturnsThroughAndAroundEveryHole) {
  const LidarModel model = LidarModel::by_name(GetParam().model);
  const SensorSetting setting = paper_setting(GetParam().setting);
  const PlacementResult result = find_placement(Target{}, setting, {model});
  ASSERT_TRUE(result.found) << result.reports.front().summary();
  const PlacementReport report = check_placement(make_scene(Target{}, result.pose), model, setting);
  EXPECT_TRUE(report.ok) << report.summary();
  EXPECT_TRUE(report.ring_free);
  const PlacementRequirements req;
  for (int h = 0; h < 4; ++h) {
    EXPECT_GE(report.returns_through_hole[h], req.min_returns_through_hole) << "hole " << h;
    EXPECT_GE(report.returns_around_hole[h], req.min_returns_around_hole) << "hole " << h;
    EXPECT_EQ(report.rings_per_hole[h], 0);
  }
  EXPECT_NE(report.summary().find("returns through holes"), std::string::npos);
}

INSTANTIATE_TEST_SUITE_P(Models, RosettePlacement,
                         ::testing::Values(RosetteCase{"avia", 1}, RosetteCase{"avia", 8},
                                           RosetteCase{"mid360", 3}, RosetteCase{"mid360", 7}),
                         [](const auto& info) { return info.param.model + "_setting" + std::to_string(info.param.setting); });

TEST(RosettePlacement, ReportsABoardOutsideTheFieldOfView) {
  // The Avia turned 0.8 rad to the left looks past a board straight ahead.
  SensorSetting setting;
  setting.yaw = 0.8;
  const Scene scene = make_scene(Target{}, BoardPose{3.0, 0.0, 0.0, 0.2, 0.0, 0.0});
  const PlacementReport report = check_placement(scene, LidarModel::avia(), setting);
  EXPECT_FALSE(report.ok);
  EXPECT_TRUE(mentions(report, "outside the field of view")) << report.summary();
}

TEST(RosettePlacement, AHoleTheFieldOfViewCutsBeyondItsCentreIsNotInView) {
  // The board slid right until one hole's centre lies just outside the
  // Avia's elliptic field of view: returns still pass through that hole and
  // land around its rim on the scanned side, but less than half of its rim
  // is in view, which no detector can place.
  const LidarModel avia = LidarModel::avia();
  const SensorSetting setting;
  const Eigen::Isometry3d T_lidar_cambody = setting.T_cambody_lidar().inverse();
  const auto outermost = [&](const Scene& scene) {
    double worst = 0.0;
    for (const Eigen::Vector2d& h : scene.target.hole_centers()) {
      const Eigen::Vector3d p = T_lidar_cambody * (scene.T_cambody_board * Eigen::Vector3d(h.x(), h.y(), 0.0));
      const double azimuth = std::atan2(p.y(), p.x()), elevation = std::atan2(p.z(), p.head<2>().norm());
      worst = std::max(worst, avia.rosette.field_of_view_position(azimuth, elevation));
    }
    return worst;
  };
  double lateral = 0.0;
  while (outermost(make_scene(Target{}, BoardPose{3.0, -lateral, 0.0, 0.2, 0.0, 0.0})) < 1.03) lateral += 0.005;
  const Scene cut = make_scene(Target{}, BoardPose{3.0, -lateral, 0.0, 0.2, 0.0, 0.0});
  const PlacementReport report = check_placement(cut, avia, setting);
  EXPECT_FALSE(report.ok);
  EXPECT_TRUE(mentions(report, "twelfths of its rim")) << report.summary();
  const auto& shares = report.rim_in_view;
  EXPECT_LT(*std::min_element(shares.begin(), shares.end()), 2.0 / 3.0) << report.summary();
  // The returns counted over the whole hole alone (the rule before) let it pass.
  PlacementRequirements counts_only;
  counts_only.min_rim_in_view = 1e-3;
  // (The camera's image margin is not this test's concern: it looks elsewhere.)
  EXPECT_FALSE(mentions(check_placement(cut, avia, setting, StereoRig{}, counts_only), "avia: hole"))
      << report.summary();
  // The same board well inside the field of view shows every rim all around.
  const Scene inside = make_scene(Target{}, BoardPose{3.0, -(lateral - 0.6), 0.0, 0.2, 0.0, 0.0});
  const PlacementReport whole = check_placement(inside, avia, setting);
  for (int h = 0; h < 4; ++h) EXPECT_GE(whole.rim_in_view[h], 11.0 / 12.0) << whole.summary();
}

TEST(RosettePlacement, ReportsTooFewReturnsOfAFarBoard) {
  // At 12 m a 0.12 m hole covers too little of the Mid-360's 360 x 59 deg in 2 s.
  SensorSetting setting;
  const Scene scene = make_scene(Target{}, BoardPose{12.0, 0.0, 2.0, 0.2, 0.0, 0.0});
  const PlacementReport report = check_placement(scene, LidarModel::mid360(), setting);
  EXPECT_FALSE(report.ok);
  EXPECT_TRUE(mentions(report, "mid360: hole")) << report.summary();
  // Longer accumulation gathers more returns.
  PlacementRequirements longer;
  longer.accumulation_time = 8.0;
  const PlacementReport slow = check_placement(scene, LidarModel::mid360(), setting, StereoRig{}, longer);
  EXPECT_GT(slow.returns_through_hole[0], 2 * report.returns_through_hole[0]);
}

SceneLayout recording_layout(double side_walls) {
  SceneLayout layout;
  layout.board_stand = true;
  layout.side_wall_distance = side_walls;
  layout.near_clutter = 3;
  layout.pillar = true;
  return layout;
}

TEST(RealScenePlacement, StandWallsClutterAndPillarStillPlaceTheBoard) {
  const std::vector<LidarModel> models{LidarModel::vlp16(), LidarModel::hdl64()};
  for (int s : {1, 3, 8}) {
    const SceneLayout layout = recording_layout(2.0);
    const PlacementResult result = find_placement(Target{}, paper_setting(s), models, StereoRig{}, layout);
    ASSERT_TRUE(result.found) << "setting " << s << "\n" << result.reports.front().summary();
    const Scene scene = make_scene(Target{}, result.pose, layout);
    EXPECT_FALSE(scene.stand.empty());
    EXPECT_EQ(scene.side_walls.size(), 2u);
    for (const LidarModel& model : models) {
      const PlacementReport report = check_placement(scene, model, paper_setting(s), StereoRig{});
      EXPECT_TRUE(report.ok) << model.name << " setting " << s << "\n" << report.summary();
    }
  }
}

TEST(RealScenePlacement, QuirkyLasersArePlacedWithTheirOwnGeometry) {
  // The HDL-64E's lower block fires from 6 cm below the origin: the check
  // follows each laser's own beam, so a placement it passes is real.
  const LidarModel model = with_quirks(LidarModel::hdl64(), LidarQuirks::all(3));
  const PlacementResult result = find_placement(Target{}, paper_setting(4), {model});
  ASSERT_TRUE(result.found);
  EXPECT_TRUE(check_placement(make_scene(Target{}, result.pose), model, paper_setting(4)).ok);
}

TEST(RealScenePlacement, SaysWhenTheBoardReachesIntoASideWall) {
  const Scene scene = make_scene(Target{}, BoardPose{3.0, 0.8, 0.0, 0.2, 0.0, 0.0}, recording_layout(1.2));
  const PlacementReport report = check_placement(scene, LidarModel::vlp16(), paper_setting(7));
  EXPECT_FALSE(report.ok);
  EXPECT_TRUE(mentions(report, "side wall")) << report.summary();
}

TEST(RealScenePlacement, SaysWhenSomethingInFrontHidesAHoleFromTheLidar) {
  // A post between the lidar and the board's top-left hole.
  SceneLayout layout;
  const BoardPose pose{3.0, 0.0, 0.0, 0.2, 0.0, 0.0};
  const Scene plain = make_scene(Target{}, pose);
  const Eigen::Vector2d hole = plain.target.hole_centers()[0];
  const Eigen::Vector3d hole_body = plain.T_cambody_board * Eigen::Vector3d(hole.x(), hole.y(), 0.0);
  Box post;
  post.T_cambody_box.translation() = 0.5 * hole_body;  // the lidar of setting 7 sits at the camera
  post.half_size = Eigen::Vector3d(0.05, 0.03, 0.3);
  layout.extra_clutter.push_back(post);
  const Scene scene = make_scene(Target{}, pose, layout);
  const PlacementReport report = check_placement(scene, LidarModel::hdl64(), paper_setting(7));
  EXPECT_FALSE(report.ok);
  EXPECT_TRUE(mentions(report, "hdl64: hole TopLeft", "occluded")) << report.summary();
}

}  // namespace
}  // namespace l2s::sim
