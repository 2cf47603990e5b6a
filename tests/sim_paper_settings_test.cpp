// The paper's nine settings as the simulator builds them, checked against
// what they must be physically: the sensor poses of Table I, a board placed
// where both sensors see its holes, the holes drawn where the geometry puts
// them, and a dataset whose ground truth is the setting's transform. The
// noise's sigma and bit-for-bit repeatability with a seed are tested beside
// the sensors they belong to (sim_lidar_test, sim_renderer_test,
// sim_dataset_test).

#include <l2s/sim/placement.hpp>
#include <l2s/sim/settings.hpp>
#include <l2s/sim/simulation.hpp>
#include <l2s/sim/stereo_renderer.hpp>
#include <l2s/sim/stereo_rig.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace l2s::sim {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Table I of the paper: t_x, t_y, t_z [m], psi (yaw), theta (pitch), phi (roll) [rad].
constexpr double kTableI[9][6] = {
    {-0.8, -0.1, 0.4, 0.0, 0.0, 0.0},          {0.0, 0.0, 0.0, 0.5, 0.0, 0.0},
    {0.0, 0.0, 0.0, 0.3, 0.1, 0.2},            {-0.3, 0.2, -0.2, 0.3, -0.1, 0.2},
    {0.0, 0.0, 0.0, 0.0, 0.1, 0.0},            {0.0, 0.0, 0.0, 0.0, 0.0, 0.4},
    {0.0, 0.0, 0.0, 0.0, 0.0, 0.0},            {-0.128, 0.418, -0.314, -0.103, -0.299, 0.110},
    {-0.433, 0.845, 1.108, -0.672, 0.258, 0.075}};

TEST(PaperSettings, SensorPosesAreTableI) {
  for (int s = 1; s <= 9; ++s) {
    const SensorSetting setting = paper_setting(s);
    const double* row = kTableI[s - 1];
    EXPECT_EQ(setting.tx, row[0]) << "setting " << s;
    EXPECT_EQ(setting.ty, row[1]) << "setting " << s;
    EXPECT_EQ(setting.tz, row[2]) << "setting " << s;
    EXPECT_EQ(setting.yaw, row[3]) << "setting " << s;
    EXPECT_EQ(setting.pitch, row[4]) << "setting " << s;
    EXPECT_EQ(setting.roll, row[5]) << "setting " << s;
    // The lidar sits where the table's translation puts it in the camera body.
    const Eigen::Vector3d origin = setting.T_cambody_lidar() * Eigen::Vector3d::Zero();
    EXPECT_LT((origin - Eigen::Vector3d(row[0], row[1], row[2])).norm(), 1e-12) << "setting " << s;
  }
}

// The ground truth written with a paper dataset is the setting's transform,
// and the simulator's lidar stands where that transform puts it.
TEST(PaperSettings, DatasetGroundTruthIsTheSettingsTransform) {
  for (int s = 1; s <= 9; ++s) {
    SimulationConfig config = SimulationConfig::paper(s, "vlp16");
    config.frames = 1;
    const DatasetSimulator simulator(config);
    EXPECT_TRUE(simulator.T_lidar_camera().isApprox(paper_setting(s).T_lidar_camera(), 1e-12)) << "setting " << s;
  }
}

/// The pixel of `p_body` in the left image of `rig`.
Eigen::Vector2d project_left(const StereoRig& rig, const Eigen::Vector3d& p_body) {
  return rig.cameras().left.project(rig.T_cambody_optical(0).inverse() * p_body);
}

// Every setting's board is placed in view, and its clean rendering shows each
// hole where the board pose puts it: the pixel at the projected centre sees
// through the hole, and the face 1.5 px outside the projected rim is board all
// round (a hole drawn 1.5 px or more off its place fails on one side).
TEST(PaperSettings, HolesAreDrawnWhereTheBoardPosePutsThem) {
  const StereoRig rig;
  const Target target;
  const std::vector<LidarModel> lidars{LidarModel::vlp16(), LidarModel::hdl32(), LidarModel::hdl64()};
  for (int s = 1; s <= 9; ++s) {
    const PlacementResult placed = find_placement(target, paper_setting(s), lidars);
    ASSERT_TRUE(placed.found) << "setting " << s;
    const Scene scene = make_scene(target, placed.pose);
    const CleanStereo clean = StereoRenderer(rig).render(RayCaster(scene));
    const CleanImage& left = clean.left;
    const auto surface = [&](const Eigen::Vector2d& px) {
      const int u = static_cast<int>(std::lround(px.x())), v = static_cast<int>(std::lround(px.y()));
      EXPECT_TRUE(u >= 0 && v >= 0 && u < left.width && v < left.height) << "setting " << s << ": off-image";
      if (u < 0 || v < 0 || u >= left.width || v >= left.height) return SurfaceId::None;
      return left.surface_at(u, v);
    };
    const Eigen::Isometry3d& T = scene.T_cambody_board;
    for (const Eigen::Vector2d& hole : target.hole_centers()) {
      const Eigen::Vector2d centre = project_left(rig, T * Eigen::Vector3d(hole.x(), hole.y(), 0.0));
      EXPECT_NE(surface(centre), SurfaceId::Board) << "setting " << s << ": hole centre " << centre.transpose();
      int outside_on_board = 0;
      const int samples = 72;
      for (int k = 0; k < samples; ++k) {
        const double a = 2.0 * kPi * k / samples;
        const Eigen::Vector2d radial(std::cos(a), std::sin(a));
        const Eigen::Vector2d rim = hole + target.hole_radius * radial;
        const Eigen::Vector2d rim_px = project_left(rig, T * Eigen::Vector3d(rim.x(), rim.y(), 0.0));
        const Eigen::Vector2d outward = (rim_px - centre).normalized();
        if (surface(rim_px + 1.5 * outward) == SurfaceId::Board) ++outside_on_board;
      }
      EXPECT_EQ(outside_on_board, samples) << "setting " << s << ": hole at " << hole.transpose();
    }
  }
}

}  // namespace
}  // namespace l2s::sim
