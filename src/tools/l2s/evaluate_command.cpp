// l2s evaluate RESULT GROUND_TRUTH: e_t and e_r of a calibration (DATASET.md),
// lidar-camera or lidar-lidar as the ground truth's key says.

#include "commands.hpp"

#include <l2s/io/transform_yaml.hpp>
#include <l2s/metrics.hpp>

#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <string>

namespace l2s::cli {

void add_evaluate_command(CLI::App& app, Runner& runner) {
  auto* command = app.add_subcommand("evaluate", "Compare a result with ground truth: e_t and e_r");
  auto result_path = std::make_shared<std::string>();
  auto truth_path = std::make_shared<std::string>();
  command->add_option("result", *result_path, "result YAML with T_lidar_camera (or T_lidar_lidar2)")->required();
  command->add_option("ground_truth", *truth_path, "ground_truth.yaml")->required();
  command->callback([&runner, result_path, truth_path] {
    runner = [result_path, truth_path] {
      // The truth says what was calibrated: a camera, or a second lidar.
      const std::string key = io::transform_key(*truth_path);
      const auto estimate = io::read_transform(*result_path, key);
      const auto truth = io::read_transform(*truth_path, key);
      std::printf("%s\n", key.c_str());
      const PoseError error = pose_error(estimate, truth);
      std::printf("e_t = %.4f m (%.1f mm)\ne_r = %.5f rad (%.3f deg)\n", error.translation,
                  error.translation * 1e3, error.rotation, error.rotation * 180.0 / M_PI);
      return 0;
    };
  });
}

}  // namespace l2s::cli
