#pragma once
// Writes files so that a reader never sees a half-written one: the content goes
// to a temporary file beside the target, which is renamed over it at the end.

#include <functional>
#include <ostream>
#include <string>

namespace l2s::detail {

/// Calls `write` with a stream to a temporary file in the target's folder, then
/// renames it to `path`. Throws FileError naming `path` when anything fails; the
/// temporary file is removed and an existing `path` is left untouched.
void write_file_atomically(const std::string& path,
                           const std::function<void(std::ostream&)>& write);

/// Same, for content already in memory.
void write_file_atomically(const std::string& path, const std::string& bytes);

}  // namespace l2s::detail
