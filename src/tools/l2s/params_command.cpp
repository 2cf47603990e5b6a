// l2s params: writes every calibrator parameter of a preset to a YAML file, the
// starting point for tuning (`l2s calibrate --params FILE`).

#include "commands.hpp"

#include <l2s/calibrator.hpp>
#include <l2s/io/calibrator_yaml.hpp>

#include <CLI/CLI.hpp>

#include <cstdio>
#include <memory>
#include <string>

namespace l2s::cli {

void add_params_command(CLI::App& app, Runner& runner) {
  auto* command = app.add_subcommand("params", "Write a preset's calibrator parameters to a YAML file");
  auto output = std::make_shared<std::string>();
  auto preset = std::make_shared<std::string>("default");
  command->add_option("output", *output, "parameters YAML to write")->required();
  command->add_option("--preset", *preset, "parameter preset")->check(CLI::IsMember({"default", "paper"}));
  command->callback([&runner, output, preset] {
    runner = [output, preset] {
      io::write_calibrator_params(*output, Calibrator::Params::preset(*preset), "preset " + *preset);
      std::printf("wrote %s (preset %s); edit it and pass it to l2s calibrate --params\n", output->c_str(),
                  preset->c_str());
      return 0;
    };
  });
}

}  // namespace l2s::cli
