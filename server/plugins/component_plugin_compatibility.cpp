#include "server/plugins/component_plugin_compatibility.hpp"

#include <cstring>

#include "control/plugin/component_plugin.hpp"
#include "server/plugins/component_plugin_text.hpp"

namespace netmc::plugins {
namespace {

template <std::size_t N>
std::string field_text(const char (&field)[N]) {
  return plugin_text(field, N, "(none)");
}

bool same_text(const char* a, const char* b, std::size_t size) { return std::strncmp(a, b, size) == 0; }

std::string compiler_series(const netmc_component_plugin& build) {
  return field_text(build.compiler) + " " + std::to_string(build.compiler_major);
}

std::string cxx_library(const netmc_component_plugin& build) {
  std::string text = field_text(build.cxx_library) + " " + std::to_string(build.cxx_library_version);
  if (field_text(build.cxx_library) == "libstdc++") {
    text += build.cxx_string_abi ? " with the C++11 std::string" : " with the pre-C++11 std::string";
  }
  return text;
}

std::string size_difference(const char* what, std::uint32_t plugin, std::uint32_t host) {
  return "sizeof(" + std::string(what) + ") is " + std::to_string(plugin) + " bytes in the plugin, " +
         std::to_string(host) + " in netmc (other headers or other compiler flags)";
}

// The first difference between the two builds beyond the ABI version and table size, if any.
std::optional<std::string> build_difference(const netmc_component_plugin& plugin, const netmc_component_plugin& host) {
  if (!same_text(plugin.netmc_version, host.netmc_version, sizeof plugin.netmc_version)) {
    return "another netmc version";
  }
  if (!same_text(plugin.compiler, host.compiler, sizeof plugin.compiler) || plugin.compiler_major != host.compiler_major) {
    return "another compiler (" + compiler_series(plugin) + ", netmc " + compiler_series(host) + ")";
  }
  if (!same_text(plugin.cxx_library, host.cxx_library, sizeof plugin.cxx_library) ||
      plugin.cxx_library_version != host.cxx_library_version || plugin.cxx_string_abi != host.cxx_string_abi) {
    return "another C++ library (" + cxx_library(plugin) + ", netmc " + cxx_library(host) + ")";
  }
  if (plugin.cplusplus != host.cplusplus) {
    return "another C++ standard (__cplusplus " + std::to_string(plugin.cplusplus) + ", netmc " +
           std::to_string(host.cplusplus) + ")";
  }
  if (plugin.axis_controller_size != host.axis_controller_size) {
    return size_difference("netmc::control::AxisController", plugin.axis_controller_size, host.axis_controller_size);
  }
  if (plugin.axis_plant_size != host.axis_plant_size) {
    return size_difference("netmc::plant::AxisPlant", plugin.axis_plant_size, host.axis_plant_size);
  }
  if (plugin.settings_size != host.settings_size) {
    return size_difference("netmc::control::ComponentSettings", plugin.settings_size, host.settings_size);
  }
  if (plugin.string_size != host.string_size) {
    return size_difference("std::string", plugin.string_size, host.string_size);
  }
  return std::nullopt;
}

}  // namespace

const netmc_component_plugin& this_netmc_component_plugin_build() {
  static constexpr netmc_component_plugin build = NETMC_COMPONENT_PLUGIN_TABLE(nullptr, nullptr, nullptr);
  return build;
}

std::string describe_component_plugin_build(const netmc_component_plugin& build) {
  std::string text = "netmc " + field_text(build.netmc_version) + " (plugin ABI " + std::to_string(build.abi_version);
  const netmc_component_plugin& host = this_netmc_component_plugin_build();
  if (build.abi_version == host.abi_version && build.table_size == host.table_size) {
    text += ", " + field_text(build.compiler) + " " + std::to_string(build.compiler_major) + "." +
            std::to_string(build.compiler_minor);
  }
  return text + ")";
}

std::optional<std::string> component_plugin_mismatch(const std::string& path, const netmc_component_plugin& plugin,
                                                     const netmc_component_plugin& host) {
  std::string why;
  if (plugin.abi_version != host.abi_version) {
    why = "another plugin ABI";
  } else if (plugin.table_size != host.table_size) {
    why = "its table has " + std::to_string(plugin.table_size) + " bytes, plugin ABI " +
          std::to_string(host.abi_version) + "'s has " + std::to_string(host.table_size) +
          " (built with an altered control/plugin/component_plugin.hpp?)";
  } else if (auto difference = build_difference(plugin, host)) {
    why = std::move(*difference);
  } else {
    return std::nullopt;
  }
  return "plugin " + path + " was built against " + describe_component_plugin_build(plugin) + "; this is " +
         describe_component_plugin_build(host) + ": " + why + "; rebuild the plugin against this netmc";
}

}  // namespace netmc::plugins
