#pragma once
// The text after `plugin:` in --controller plugin:PATH.so[:key=value,...] and
// --plant plugin:PATH.so[:key=value,...]: the shared object's path, then optionally its settings
// as comma-separated key=value pairs with numeric values. The path ends at the first ':' and may
// hold neither ':' nor ','. Keys are [A-Za-z0-9_.-] and unique; values are finite decimal numbers
// ("20", "-1.5e-3"). Everything is bounded, so a typo cannot hand a plugin megabytes.

#include <cstddef>
#include <map>
#include <string>
#include <string_view>

namespace netmc::plugins {

// What a plugin's factory receives: key -> value (control/plugin/component_plugin.hpp's
// netmc::control::ComponentSettings).
using PluginSettings = std::map<std::string, double>;

struct ComponentPluginSpec {
  std::string path;
  PluginSettings settings;
};

inline constexpr std::size_t kMaxComponentPluginPathLength = 4096;
inline constexpr std::size_t kMaxComponentPluginKeyLength = 64;
inline constexpr std::size_t kMaxComponentPluginValueLength = 64;
inline constexpr std::size_t kMaxComponentPluginSettings = 64;

// Throws one std::invalid_argument naming the key or the part that is wrong, e.g.
// "plugin: kp=fast: the value of kp is not a finite decimal number".
ComponentPluginSpec parse_component_plugin_spec(const std::string& text);

// True for a key a setting may have: 1 to kMaxComponentPluginKeyLength of [A-Za-z0-9_.-].
bool is_component_plugin_key(std::string_view key);

// The number `text` spells, or std::invalid_argument naming `key`: finite, decimal (digits, one
// '.', an optional sign and exponent), nothing before or after it.
double parse_component_plugin_value(std::string_view key, std::string_view text);

}  // namespace netmc::plugins
