#pragma once
// A stereo rig rolled about its optical axis against the lidar and the board
// (issue 8, "any mounting"). The simulator builds its world in the camera
// body frame, so a rig rolled by `degrees` in the world is simulated by
// turning everything it looks at the other way about the body x axis: the
// lidar's pose and the board's pose. The wall behind the board is
// perpendicular to body x and stays; the ground stays below the camera (a
// floor seen by a rolled camera is then a ceiling: nothing the calibration
// uses). The board pose must be given (placed for the unrolled rig).

#include <l2s/pose.hpp>
#include <l2s/sim/simulation.hpp>

#include <Eigen/Geometry>
#include <cmath>

namespace l2s::test {

inline sim::SimulationConfig rolled_rig(sim::SimulationConfig config, const sim::BoardPose& board, double degrees) {
  const Eigen::Matrix3d R_turn = Eigen::AngleAxisd(-degrees * M_PI / 180.0, Eigen::Vector3d::UnitX()).toRotationMatrix();
  const Eigen::Isometry3d T_lidar = config.setting.T_cambody_lidar();
  const Eigen::Vector3d t_lidar = R_turn * T_lidar.translation();
  const Eigen::Vector3d rpy_lidar = roll_pitch_yaw(R_turn * T_lidar.linear());
  config.setting_index = 0;
  config.setting = {t_lidar.x(), t_lidar.y(), t_lidar.z(), rpy_lidar[2], rpy_lidar[1], rpy_lidar[0]};

  // BoardPose: R_cambody_board = Rz Ry Rx * R_facing, R_facing the pose of all zeros.
  const Eigen::Matrix3d R_facing = sim::BoardPose{0, 0, 0, 0, 0, 0}.T_cambody_board().linear();
  const Eigen::Isometry3d T_board = board.T_cambody_board();
  const Eigen::Vector3d t_board = R_turn * T_board.translation();
  const Eigen::Vector3d rpy_board = roll_pitch_yaw(R_turn * T_board.linear() * R_facing.transpose());
  config.board_pose = sim::BoardPose{t_board.x(), t_board.y(), t_board.z(), rpy_board[2], rpy_board[1], rpy_board[0]};
  return config;
}

}  // namespace l2s::test
