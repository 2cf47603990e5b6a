// The scene elements of real recordings: a stand under the board, corridor
// side walls, low clutter between the sensors and the board, a pillar. They
// are off by default, sit where they are meant to, and the lidar hits them.

#include <l2s/sim/lidar_simulator.hpp>
#include <l2s/sim/placement.hpp>
#include <l2s/sim/ray_caster.hpp>
#include <l2s/sim/settings.hpp>

#include <l2s/error.hpp>

#include <gtest/gtest.h>

#include <map>

namespace l2s::sim {
namespace {

const BoardPose kPose{3.0, 0.1, -0.1, 0.2, 0.05, 0.03};

SceneLayout everything() {
  SceneLayout layout;
  layout.board_stand = true;
  layout.side_wall_distance = 2.0;
  layout.near_clutter = 3;
  layout.pillar = true;
  return layout;
}

TEST(SceneElements, OffByDefault) {
  const Scene scene = make_scene(Target{}, kPose);
  EXPECT_TRUE(scene.stand.empty());
  EXPECT_TRUE(scene.side_walls.empty());
  EXPECT_TRUE(scene.pillars.empty());
  EXPECT_EQ(scene.clutter.size(), 2u);  // the paper's two boxes beside the board
  EXPECT_EQ(scene.side_wall_distance, 0.0);
}

TEST(SceneElements, StandHoldsTheBoardBelowItsHoles) {
  const Scene scene = make_scene(Target{}, kPose, everything());
  ASSERT_EQ(scene.stand.size(), 2u);  // post and base
  const Box& post = scene.stand[0];
  const Box& base = scene.stand[1];
  const Target& t = scene.target;
  // The post reaches from the ground to above the board's bottom edge ...
  const double post_bottom = post.T_cambody_box.translation().z() - post.half_size.z();
  const double post_top = post.T_cambody_box.translation().z() + post.half_size.z();
  EXPECT_NEAR(post_bottom, scene.ground_z, 1e-9);
  const Eigen::Vector3d bottom_edge = scene.T_cambody_board * Eigen::Vector3d(0.0, -0.5 * t.board_height, 0.0);
  EXPECT_GT(post_top, bottom_edge.z() + 0.01);
  // ... but stays below the lowest hole, just behind the board's back face.
  const Eigen::Vector3d hole = scene.T_cambody_board * Eigen::Vector3d(0.0, -0.5 * t.hole_spacing_y - t.hole_radius, 0.0);
  EXPECT_LT(post_top, hole.z());
  // (The post is vertical; the board is tilted a little, so compare at the bottom edge.)
  const Eigen::Vector3d post_board = scene.T_cambody_board.inverse() *
      (post.T_cambody_box.translation() + Eigen::Vector3d(0.0, 0.0, bottom_edge.z() - post.T_cambody_box.translation().z()));
  EXPECT_NEAR(post_board.x(), 0.0, 0.01);
  EXPECT_LT(post_board.z(), -t.board_thickness);
  EXPECT_GT(post_board.z(), -t.board_thickness - 0.05);
  EXPECT_NEAR(base.T_cambody_box.translation().z() - base.half_size.z(), scene.ground_z, 1e-9);
}

TEST(SceneElements, NearClutterStaysBelowTheSightLines) {
  const Scene scene = make_scene(Target{}, kPose, everything());
  // The paper's two boxes beside the board would stand behind it in a 2 m
  // corridor, where rays through the holes could end on them: they go.
  ASSERT_EQ(scene.clutter.size(), 3u);
  double lowest_board = 1e9;
  for (double sx : {-0.5, 0.5})
    for (double sy : {-0.5, 0.5})
      lowest_board = std::min(lowest_board, (scene.T_cambody_board * Eigen::Vector3d(sx * 1.4, sy * 1.0, 0.0)).z());
  int near = 0;
  for (const Box& box : scene.clutter) {
    const Eigen::Vector3d c = box.T_cambody_box.translation();
    if (c.x() > kPose.x) continue;
    ++near;
    EXPECT_GT(c.x(), 0.5);
    EXPECT_LT(c.z() + box.half_size.z(), lowest_board - 0.04);
    EXPECT_LE(c.z() + box.half_size.z(), scene.ground_z + 0.45 + 1e-9);
    EXPECT_LT(std::abs(c.y()) + box.half_size.head<2>().norm(), 2.0);  // inside the corridor
  }
  EXPECT_EQ(near, 3);
  // Nothing hides the board: the default check passes for the cameras and a lidar.
  const PlacementReport report = check_placement(scene, LidarModel::hdl64(), paper_setting(1));
  for (const std::string& f : report.failures) EXPECT_EQ(f.find("occluded"), std::string::npos) << f;
}

TEST(SceneElements, TheLidarHitsEveryElement) {
  const Scene scene = make_scene(Target{}, kPose, everything());
  const RayCaster caster(scene);
  std::vector<SurfaceId> surfaces;
  // Setting 4's lidar sits 1.3 m above the ground: its lowest beams reach the low boxes.
  LidarSimulator(LidarModel::hdl64()).sweep(caster, paper_setting(4).T_cambody_lidar(), 0, &surfaces);
  std::map<SurfaceId, int> hits;
  for (SurfaceId s : surfaces) ++hits[s];
  for (SurfaceId s : {SurfaceId::Board, SurfaceId::Stand, SurfaceId::SideWall, SurfaceId::Clutter,
                      SurfaceId::Pillar, SurfaceId::Ground, SurfaceId::Wall})
    EXPECT_GT(hits[s], 10) << "surface " << static_cast<int>(s);
  // The side walls are parallel to the driving direction at +-2 m.
  const Hit left = caster.cast(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitY());
  EXPECT_EQ(left.surface, SurfaceId::SideWall);
  EXPECT_NEAR(left.t, 2.0, 1e-12);
}

TEST(SceneElements, InvalidLayoutNamesTheField) {
  SceneLayout layout;
  layout.side_wall_distance = 0.3;
  try {
    make_scene(Target{}, kPose, layout);
    FAIL() << "expected ParamError";
  } catch (const ParamError& e) {
    EXPECT_EQ(e.field(), "scene.side_wall_distance");
  }
  layout = SceneLayout{};
  layout.near_clutter = 20;
  EXPECT_THROW(make_scene(Target{}, kPose, layout), ParamError);
}

}  // namespace
}  // namespace l2s::sim
