#pragma once
// Output files written whole or not at all, without trusting the directory: the content goes to
// a fresh file created exclusively under an unpredictable name beside the target (mkstemp: it
// never opens a planted file or follows a planted symlink) and is renamed over the target (the
// rename replaces a symlink there, it does not write through it).

#include <filesystem>
#include <string>

namespace netmc::cli {

// Creates an empty file TARGET.XXXXXX (mode 0644) beside `target` and returns its path. Throws
// std::runtime_error naming the target when it cannot.
std::filesystem::path create_exclusive_temporary(const std::filesystem::path& target);

// Writes `content` to `path` through such a temporary; on failure nothing is left behind and
// std::runtime_error names the path.
void write_file_atomically(const std::string& path, const std::string& content);

}  // namespace netmc::cli
