#pragma once
// Whether a component plugin's build matches this netmc's: the check netmc runs on the plain C
// head of a plugin's table (control/plugin/component_plugin.hpp) before it calls any function
// of the plugin. In order: ABI version, table size, netmc version, compiler (name and major
// version), C++ library (name, release, std::string ABI), C++ standard, and the sizes of the
// interface classes, of the settings map and of std::string. The first difference found is the
// refusal, a message that names both builds:
//   "plugin libx.so was built against netmc 0.1.0 (plugin ABI 1, gcc 12.2); this is netmc 0.2.0
//    (plugin ABI 1, gcc 12.2): another netmc version; rebuild the plugin against this netmc"
// Every field that holds text is read within its bounds and shown as printable ASCII only.

#include <optional>
#include <string>

struct netmc_component_plugin;

namespace netmc::plugins {

// The table a plugin built with this netmc, its compiler and C++ library would carry (no
// functions).
const netmc_component_plugin& this_netmc_component_plugin_build();

// "netmc 0.1.0 (plugin ABI 1, gcc 12.2)". Only the head every ABI version keeps (ABI version and
// netmc version) is read when the ABI version is not this netmc's.
std::string describe_component_plugin_build(const netmc_component_plugin& build);

// The refusal of `plugin` (loaded from `path`) by a netmc built as `host`, or nothing when they
// match. Reads no field past those the ABI version and table size vouch for.
std::optional<std::string> component_plugin_mismatch(const std::string& path, const netmc_component_plugin& plugin,
                                                     const netmc_component_plugin& host =
                                                         this_netmc_component_plugin_build());

}  // namespace netmc::plugins
