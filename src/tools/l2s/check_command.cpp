// l2s check DATASET RESULT.yaml: checks a transform (any calibration result,
// an old one, a hand-made one) against a dataset's scene, without ground
// truth: runs both branches on evenly spread frames, then the calibration
// check, prints its report and exits 0 (ok), 3 (suspect) or 1 (failed).

#include "commands.hpp"
#include "progress_bar.hpp"

#include <l2s/calibration_check.hpp>
#include <l2s/check_frames.hpp>
#include <l2s/io/calibrator_yaml.hpp>
#include <l2s/io/dataset.hpp>
#include <l2s/io/image_io.hpp>
#include <l2s/io/transform_yaml.hpp>
#include <l2s/metrics.hpp>
#include <l2s/viz/overlay.hpp>

#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

namespace l2s::cli {
namespace {

struct CheckOptions {
  std::string dataset;
  std::string result;
  std::string key = "T_lidar_camera";
  std::string params_file;
  std::string preset = "default";
  std::string overlay;
  int frames = 8;
};

/// Exit code of a verdict: 0 ok, 3 suspect, 1 failed.
int exit_code(CalibrationCheck::Verdict verdict) {
  switch (verdict) {
    case CalibrationCheck::Verdict::Ok: return 0;
    case CalibrationCheck::Verdict::Suspect: return 3;
    case CalibrationCheck::Verdict::Failed: return 1;
  }
  return 1;
}

int run_check(const CheckOptions& options) {
  const auto dataset = io::Dataset::open(options.dataset);
  const Eigen::Isometry3d T_lidar_camera = io::read_transform(options.result, options.key);
  const Calibrator::Params params = params_from(options.preset, options.params_file);
  params.validate();
  const SceneObserver observer(params.observer);

  // Evenly spread frames: a static board gives the same scene in all of them,
  // a moved one shows each pose.
  const std::size_t count = std::min<std::size_t>(static_cast<std::size_t>(options.frames), dataset.size());
  std::vector<CheckFrame> frames;
  std::vector<std::size_t> indices;
  ProgressBar progress("check", count);
  for (std::size_t k = 0; k < count; ++k) {
    const std::size_t index = (2 * k + 1) * dataset.size() / (2 * count);
    const io::Frame frame = dataset.load(index);
    frames.push_back(observe_frame(frame.lidar, frame.left, frame.right, dataset.cameras(), dataset.target(), params,
                                   observer, frame.stem));
    indices.push_back(index);
    progress.update(k + 1);
  }
  progress.finish();

  const CalibrationCheck check(dataset.cameras(), dataset.target(), params.check);
  const CalibrationCheck::Report report = check.check(frames, T_lidar_camera);
  std::printf("%s", describe(report).c_str());
  if (const auto truth = dataset.ground_truth()) {
    const PoseError error = pose_error(T_lidar_camera, *truth);
    std::printf("truth     e_t = %.1f mm, e_r = %.3f deg (ground_truth.yaml; the check did not use it)\n",
                error.translation * 1e3, error.rotation * 180.0 / M_PI);
  }
  if (!options.overlay.empty() && !frames.empty()) {
    const io::Frame frame = dataset.load(indices.back());
    const std::string caption = std::string("check: ") + verdict_name(report.verdict) + " | frame " + frame.stem +
                                " | yellow/magenta: lidar depth edges, blue: image edges";
    io::write_png(options.overlay, render_edge_overlay(frame.left, dataset.cameras(), frames.back().lidar,
                                                       T_lidar_camera, observer, caption));
    std::printf("wrote     %s\n", options.overlay.c_str());
  }
  if (report.verdict != CalibrationCheck::Verdict::Ok)
    std::fprintf(stderr, "l2s: the transform is %s by the scene check\n",
                 report.verdict == CalibrationCheck::Verdict::Failed ? "contradicted (failed)" : "suspect");
  return exit_code(report.verdict);
}

}  // namespace

void add_check_command(CLI::App& app, Runner& runner) {
  auto* command = app.add_subcommand(
      "check", "Check a transform against a dataset's scene without ground truth (exit 0 ok, 3 suspect, 1 failed)");
  auto options = std::make_shared<CheckOptions>();
  command->add_option("dataset", options->dataset, "dataset folder (DATASET.md)")->required();
  command->add_option("result", options->result, "YAML file holding the transform (a calibration result)")
      ->required()
      ->check(CLI::ExistingFile);
  command->add_option("--key", options->key, "key of the transform in the file (p_lidar = T * p_camera)");
  command->add_option("--frames", options->frames, "frames to check, evenly spread")
      ->check(CLI::PositiveNumber);
  command->add_option("--params", options->params_file, "parameters YAML (branches, observer, check thresholds)")
      ->check(CLI::ExistingFile);
  command->add_option("--preset", options->preset, "parameter preset")->check(CLI::IsMember({"default", "paper"}));
  command->add_option("--overlay", options->overlay, "write the check's overlay PNG here");
  command->callback([&runner, options] { runner = [options] { return run_check(*options); }; });
}

}  // namespace l2s::cli
