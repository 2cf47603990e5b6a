// Sensors mounted as users mount them: a stereo rig rolled about its optical
// axis, a lidar upside down. The simulator must image the same world from
// the turned sensor and state the truth in the turned sensor's frame.

#include <l2s/sim/mounting_draw.hpp>
#include <l2s/sim/simulation.hpp>

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <cstdlib>
#include <random>

namespace l2s::sim {
namespace {

constexpr double kPi = 3.141592653589793;

SimulationConfig small_paper_scene() {
  SimulationConfig config = SimulationConfig::paper(1, "vlp16");
  config.frames = 1;
  config.noise_factor = 0.0;  // the images compared pixel by pixel
  config.seed = 7;
  config.rig.width = 320;
  config.rig.height = 240;
  config.threads = 1;
  return config;
}

/// Mean absolute difference of `a` and `b` turned by 180 deg (or as they are).
double mean_difference(const Image& a, const Image& b, bool turned) {
  double sum = 0.0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      const int bx = turned ? a.width - 1 - x : x, by = turned ? a.height - 1 - y : y;
      sum += std::abs(static_cast<int>(a.at(x, y)) - static_cast<int>(b.at(bx, by)));
    }
  return sum / (static_cast<double>(a.width) * a.height);
}

// A pinhole with its principal point at the image centre, turned by 180 deg
// about its optical axis, sees the same scene upside down: pixel (x, y)
// shows what (W-1-x, H-1-y) showed. The holes' truth in the camera frame
// turns with it: x and y change sign, depth stays.
TEST(SimMounting, ARigRolled180DegreesSeesTheBoardUpsideDownWhereTheTruthPutsIt) {
  const SimulationConfig level_config = small_paper_scene();
  const DatasetSimulator level(level_config);
  SimulationConfig rolled_config = level_config;
  rolled_config.rig.roll = kPi;
  rolled_config.board_pose = level.board_pose();  // the same world: only the rig turns
  const DatasetSimulator rolled(rolled_config);

  const Image level_left = level.frame(0).left, rolled_left = rolled.frame(0).left;
  const double turned = mean_difference(level_left, rolled_left, true);
  const double as_is = mean_difference(level_left, rolled_left, false);
  EXPECT_LT(turned, 1.0) << "gray levels";
  EXPECT_GT(as_is, 10.0 * turned + 2.0) << "the rolled image must differ from the level one";

  const auto level_holes = level.true_hole_centers(), rolled_holes = rolled.true_hole_centers();
  for (std::size_t h = 0; h < level_holes.camera.size(); ++h) {
    const Eigen::Vector3d expected(-level_holes.camera[h].x(), -level_holes.camera[h].y(), level_holes.camera[h].z());
    EXPECT_LT((rolled_holes.camera[h] - expected).norm(), 1e-9) << "hole " << h;
    EXPECT_LT((rolled_holes.lidar[h] - level_holes.lidar[h]).norm(), 1e-9) << "hole " << h;
  }
  // The truth is the transform the rolled images were made with.
  const Eigen::Isometry3d turn(Eigen::AngleAxisd(kPi, Eigen::Vector3d::UnitZ()));
  EXPECT_TRUE(rolled.T_lidar_camera().isApprox(level.T_lidar_camera() * turn, 1e-12));
}

// Rolled by +90 deg (right-handed about the forward axis: the camera's right
// points down), the truth turns by 90 deg about the optical axis: a point
// right of the image centre in the level camera lies above it (-y) in the
// rolled one, and one below it lies right of it.
TEST(SimMounting, ARigRolled90DegreesTurnsTheTruthAboutTheOpticalAxis) {
  const SimulationConfig level_config = small_paper_scene();
  const DatasetSimulator level(level_config);
  SimulationConfig rolled_config = level_config;
  rolled_config.rig.roll = 0.5 * kPi;
  rolled_config.board_pose = level.board_pose();
  const DatasetSimulator rolled(rolled_config);
  const auto level_holes = level.true_hole_centers(), rolled_holes = rolled.true_hole_centers();
  for (std::size_t h = 0; h < level_holes.camera.size(); ++h) {
    const Eigen::Vector3d& p = level_holes.camera[h];
    // The camera turned by +90 deg about its optical axis: p_rolled = Rz(-90 deg) p.
    EXPECT_LT((rolled_holes.camera[h] - Eigen::Vector3d(p.y(), -p.x(), p.z())).norm(), 1e-9) << "hole " << h;
  }
}

/// Lidar returns within `tolerance` of the board's plane and inside the
/// rectangle its hole centres span, widened by `margin` (lidar frame).
int returns_on_board(const LidarCloud& sweep, const DatasetSimulator::HoleTruth& truth, double tolerance,
                     double margin) {
  const auto& c = truth.lidar;  // TL, TR, BL, BR
  const Eigen::Vector3d origin = 0.25 * (c[0] + c[1] + c[2] + c[3]);
  const Eigen::Vector3d across = (c[1] - c[0]).normalized(), down = (c[2] - c[0]).normalized();
  const Eigen::Vector3d normal = across.cross(down).normalized();
  const double half_across = 0.5 * (c[1] - c[0]).norm() + margin, half_down = 0.5 * (c[2] - c[0]).norm() + margin;
  int count = 0;
  for (const Eigen::Vector3d& p : sweep.points) {
    if (!p.allFinite()) continue;
    const Eigen::Vector3d d = p - origin;
    count += std::abs(d.dot(normal)) < tolerance && std::abs(d.dot(across)) < half_across &&
             std::abs(d.dot(down)) < half_down;
  }
  return count;
}

// A lidar mounted upside down (rolled 180 deg about its forward axis) sees
// the board with the rings' order reversed; its returns lie on the true
// board plane, stated in its own (upside-down) frame, as many as upright.
TEST(SimMounting, AnUpsideDownLidarsBoardReturnsLieOnTheTrueBoardPlane) {
  SimulationConfig upright_config = small_paper_scene();
  const DatasetSimulator upright(upright_config);
  SimulationConfig flipped_config = upright_config;
  flipped_config.setting.roll += kPi;
  flipped_config.board_pose = upright.board_pose();
  const DatasetSimulator flipped(flipped_config);

  const auto upright_truth = upright.true_hole_centers(), flipped_truth = flipped.true_hole_centers();
  // The truth in the flipped frame: y and z change sign.
  for (std::size_t h = 0; h < upright_truth.lidar.size(); ++h) {
    const Eigen::Vector3d& p = upright_truth.lidar[h];
    EXPECT_LT((flipped_truth.lidar[h] - Eigen::Vector3d(p.x(), -p.y(), -p.z())).norm(), 1e-9) << "hole " << h;
  }
  const int upright_on_board = returns_on_board(upright.sweep(0), upright_truth, 0.005, 0.15);
  const int flipped_on_board = returns_on_board(flipped.sweep(0), flipped_truth, 0.005, 0.15);
  EXPECT_GT(upright_on_board, 100);
  EXPECT_GT(flipped_on_board, 0.7 * upright_on_board);
  EXPECT_LT(flipped_on_board, 1.3 * upright_on_board);
  // ... and none of the flipped returns lies on the board as the upright frame would put it.
  EXPECT_LT(returns_on_board(flipped.sweep(0), upright_truth, 0.005, 0.15), flipped_on_board / 10);
}

// The draws' shares, over many draws: a third of the rigs rolled beyond
// 20 deg, among them on their side and upside down; 15 % of the lidars
// upside down; a quarter of the rigs one of the three rigs users bring
// besides the common ones, each valid and rectifiable.
TEST(MountingDraw, RollsFlipsAndRigsComeInTheirShares) {
  constexpr int kDraws = 3000;
  int rolled = 0, on_side = 0, upside_down = 0, flipped = 0, special = 0, toed_in = 0;
  for (int i = 0; i < kDraws; ++i) {
    std::mt19937_64 mounts(static_cast<std::uint64_t>(i)), rigs(static_cast<std::uint64_t>(i) + 1000003);
    StereoRig rig;
    SensorSetting lidar;
    draw_mounting(mounts, &rig, &lidar);
    const double roll_deg = std::abs(std::remainder(rig.roll, 2.0 * kPi)) * 180.0 / kPi;
    rolled += roll_deg > 19.999;
    on_side += std::abs(roll_deg - 90.0) < 1e-9;
    upside_down += std::abs(roll_deg - 180.0) < 1e-9;
    EXPECT_TRUE(roll_deg < 1e-12 || roll_deg > 19.999) << "level or rolled beyond 20 deg";
    flipped += std::cos(lidar.roll) < 0.0;
    const StereoRig drawn = rig;
    draw_special_rig(rigs, &rig);
    EXPECT_EQ(rig.roll, drawn.roll);
    if (rig.width == drawn.width && rig.baseline == drawn.baseline) continue;
    ++special;
    toed_in += rig.right_rotation.y() < -0.9 * kPi / 180.0;
    if (i < 40) EXPECT_NO_THROW(rig.cameras()) << rig.width << "x" << rig.height;
  }
  EXPECT_NEAR(rolled, kDraws / 3, kDraws / 30);
  EXPECT_NEAR(on_side, kDraws / 6, kDraws / 30);
  EXPECT_NEAR(upside_down, kDraws / 12, kDraws / 30);
  EXPECT_NEAR(flipped, 0.15 * kDraws, kDraws / 30);
  EXPECT_NEAR(special, kDraws / 4, kDraws / 30);
  EXPECT_NEAR(toed_in, special / 3, special / 10) << "the 5 MP wide pairs";
}

}  // namespace
}  // namespace l2s::sim
