#pragma once
// target.yaml: the board geometry (DATASET.md).

#include <l2s/export.hpp>
#include <l2s/target.hpp>

#include <string>

namespace l2s::io {

/// Reads target.yaml; keys that are absent keep the defaults of Target, unknown
/// keys are ignored, an empty file means all defaults. Throws FileError on
/// malformed YAML, non-numeric values or an impossible board (Target::validate's
/// message, prefixed with the file).
L2S_EXPORT Target read_target(const std::string& path);

/// Reads target.yaml when the file exists, otherwise returns the defaults.
L2S_EXPORT Target read_target_or_default(const std::string& path);

/// Writes target.yaml atomically.
L2S_EXPORT void write_target(const std::string& path, const Target& target);

}  // namespace l2s::io
