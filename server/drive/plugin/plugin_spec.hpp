#pragma once
// The text after `plugin:` in `--drive plugin:PATH.so[:key=value,...]`: the plugin's path, then
// optionally its configuration as comma-separated key=value pairs. The path ends at the first
// ':' (a path with ':' in it cannot be named). Keys are [A-Za-z0-9_.-], unique; values are
// printable ASCII without ','. Everything is bounded, so a typo cannot hand a plugin megabytes.

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace netmc::drive {

struct PluginSpec {
  std::string path;
  std::vector<std::pair<std::string, std::string>> settings;  // in the order given
};

inline constexpr std::size_t kMaxPluginPathLength = 4096;
inline constexpr std::size_t kMaxPluginKeyLength = 64;
inline constexpr std::size_t kMaxPluginValueLength = 256;
inline constexpr std::size_t kMaxPluginSettings = 64;

// Throws std::invalid_argument naming what is wrong: "plugin:lab.so:gain: 'gain' has no '='".
PluginSpec parse_plugin_spec(const std::string& text);

}  // namespace netmc::drive
