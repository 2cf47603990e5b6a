// l2s: lidar-stereo calibration from the command line.
// Exit codes: 0 success, 1 bad input or failed job (one-line reason on stderr),
// 2 bad command line, 3 a transform the scene check finds suspect (l2s check).

#include "allocator_tuning.hpp"
#include "commands.hpp"

#include <l2s/error.hpp>

#include <CLI/CLI.hpp>

#include <exception>
#include <iostream>

int main(int argc, char** argv) {
  l2s::cli::keep_large_buffers();
  CLI::App app{"l2s: automatic lidar-stereo extrinsic calibration (l2scalib)"};
  app.require_subcommand(1);
  // Every option's help shows its default value (options added after this inherit it).
  app.option_defaults()->always_capture_default();
  app.footer(
      "Exit codes: 0 success; 1 bad input or a failed job (one line on stderr naming the file and the fault); "
      "2 bad command line; 3 a transform the scene check finds suspect (l2s check).\n"
      "Each sub-command's options: l2s SUBCOMMAND --help. Manual: README.md and docs/ of l2scalib.");
  l2s::cli::Runner runner;
  l2s::cli::add_simulate_command(app, runner);
  l2s::cli::add_calibrate_command(app, runner);
  l2s::cli::add_info_command(app, runner);
  l2s::cli::add_extract_command(app, runner);
  l2s::cli::add_params_command(app, runner);
  l2s::cli::add_evaluate_command(app, runner);
  l2s::cli::add_suite_command(app, runner);
  l2s::cli::add_detect_command(app, runner);
  l2s::cli::add_check_command(app, runner);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    return app.exit(error) == 0 ? 0 : 2;
  }
  try {
    return runner ? runner() : 2;
  } catch (const l2s::Error& error) {
    std::cerr << "l2s: error: " << error.what() << "\n";
  } catch (const std::exception& error) {
    std::cerr << "l2s: unexpected error: " << error.what() << "\n";
  }
  return 1;
}
