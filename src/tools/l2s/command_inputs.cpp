// Inputs several sub-commands share (commands.hpp).
#include "commands.hpp"

#include <l2s/io/calibrator_yaml.hpp>

#include <cstdio>

namespace l2s::cli {

io::Dataset open_dataset_warning(const std::string& folder) {
  io::Dataset dataset = io::Dataset::open(folder);
  for (const std::string& warning : dataset.warnings()) std::fprintf(stderr, "l2s: warning: %s\n", warning.c_str());
  return dataset;
}

Calibrator::Params params_from(const std::string& preset, const std::string& params_file) {
  return params_file.empty() ? Calibrator::Params::preset(preset) : io::read_calibrator_params(params_file);
}

}  // namespace l2s::cli
