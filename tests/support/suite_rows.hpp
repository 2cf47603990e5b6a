#pragma once
// A results.csv row with every field set, for the suite's tests.

#include <l2s/sim/suite.hpp>

namespace l2s::sim {

inline SuiteRow sample_row() {
  SuiteRow row;
  row.experiment = "noise";
  row.setting = 4;
  row.lidar = "vlp16";
  row.noise_k = 2.0;
  row.frames = 30;
  row.preset = "paper";
  row.seed = 123456789;
  row.repetition = 2;
  row.success = true;
  row.e_t = 0.0012345678901234567;
  row.e_r = 1.0 / 3.0;
  row.lidar_frames = 29;
  row.camera_frames = 30;
  row.wall_s = 4.25;
  return row;
}

}  // namespace l2s::sim
