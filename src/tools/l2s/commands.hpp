#pragma once
// Each sub-command of `l2s` registers its options on the CLI11 app and sets the
// function that runs it; main() parses, runs and maps errors to exit codes.

#include <CLI/CLI.hpp>

#include <functional>

namespace l2s::cli {

/// Runs a parsed sub-command; returns the process exit code.
using Runner = std::function<int()>;

void add_calibrate_command(CLI::App& app, Runner& runner);
void add_info_command(CLI::App& app, Runner& runner);
void add_params_command(CLI::App& app, Runner& runner);
void add_evaluate_command(CLI::App& app, Runner& runner);
void add_simulate_command(CLI::App& app, Runner& runner);
void add_suite_command(CLI::App& app, Runner& runner);
void add_detect_command(CLI::App& app, Runner& runner);
void add_check_command(CLI::App& app, Runner& runner);

}  // namespace l2s::cli
