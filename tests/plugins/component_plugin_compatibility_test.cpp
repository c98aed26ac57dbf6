// The build check on a plugin table's plain C head: each field that differs from this netmc's
// own build is refused with a message naming both builds, in the order the fields are checked;
// an identical build passes. Tables here are this build's, changed one field at a time.
#include "server/plugins/component_plugin_compatibility.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include "control/plugin/component_plugin.hpp"

namespace netmc::plugins {
namespace {

netmc_component_plugin this_build() { return this_netmc_component_plugin_build(); }

// "gcc 12.2" for the compiler this test is built with.
std::string compiler() {
  return std::string(NETMC_COMPONENT_PLUGIN_COMPILER) + " " + std::to_string(NETMC_COMPONENT_PLUGIN_COMPILER_MAJOR) +
         "." + std::to_string(NETMC_COMPONENT_PLUGIN_COMPILER_MINOR);
}

const std::string kHost = "netmc " NETMC_VERSION " (plugin ABI 1, " + compiler() + ")";

std::string refusal(const netmc_component_plugin& plugin) {
  return component_plugin_mismatch("libx.so", plugin).value_or("");
}

TEST(ComponentPluginCompatibility, ThisBuildDescribesItselfAndPasses) {
  EXPECT_EQ(describe_component_plugin_build(this_build()), kHost);
  EXPECT_FALSE(component_plugin_mismatch("libx.so", this_build()));
  EXPECT_EQ(this_build().abi_version, static_cast<std::uint32_t>(NETMC_COMPONENT_PLUGIN_ABI));
  EXPECT_STREQ(this_build().netmc_version, NETMC_VERSION);
  EXPECT_EQ(this_build().cplusplus, __cplusplus);
}

TEST(ComponentPluginCompatibility, RefusesAnotherNetmcVersionNamingBoth) {
  auto plugin = this_build();
  std::strcpy(plugin.netmc_version, "0.0.1");
  EXPECT_EQ(refusal(plugin), "plugin libx.so was built against netmc 0.0.1 (plugin ABI 1, " + compiler() +
                                 "); this is " + kHost + ": another netmc version; rebuild the plugin against this netmc");
}

TEST(ComponentPluginCompatibility, RefusesAnotherAbiReadingOnlyTheHeadEveryVersionKeeps) {
  auto plugin = this_build();
  plugin.abi_version = 2;
  std::strcpy(plugin.compiler, "unread");
  EXPECT_EQ(refusal(plugin), "plugin libx.so was built against netmc " NETMC_VERSION " (plugin ABI 2); this is " + kHost +
                                 ": another plugin ABI; rebuild the plugin against this netmc");
}

TEST(ComponentPluginCompatibility, RefusesATableOfAnotherSize) {
  auto plugin = this_build();
  plugin.table_size -= 8;
  EXPECT_EQ(refusal(plugin), "plugin libx.so was built against netmc " NETMC_VERSION " (plugin ABI 1); this is " + kHost +
                                 ": its table has " + std::to_string(sizeof(netmc_component_plugin) - 8) +
                                 " bytes, plugin ABI 1's has " + std::to_string(sizeof(netmc_component_plugin)) +
                                 " (built with an altered control/plugin/component_plugin.hpp?); rebuild the plugin "
                                 "against this netmc");
}

TEST(ComponentPluginCompatibility, RefusesAnotherCompilerOrMajorVersionButNotAnotherMinor) {
  auto plugin = this_build();
  std::strcpy(plugin.compiler, "clang");
  plugin.compiler_major = 16;
  plugin.compiler_minor = 0;
  const std::string host_series = std::string(NETMC_COMPONENT_PLUGIN_COMPILER) + " " +
                                  std::to_string(NETMC_COMPONENT_PLUGIN_COMPILER_MAJOR);
  EXPECT_EQ(refusal(plugin), "plugin libx.so was built against netmc " NETMC_VERSION " (plugin ABI 1, clang 16.0); this is " +
                                 kHost + ": another compiler (clang 16, netmc " + host_series +
                                 "); rebuild the plugin against this netmc");
  plugin = this_build();
  plugin.compiler_major += 1;
  EXPECT_NE(refusal(plugin).find(": another compiler ("), std::string::npos) << refusal(plugin);
  plugin = this_build();
  plugin.compiler_minor += 1;
  EXPECT_EQ(refusal(plugin), "");
}

TEST(ComponentPluginCompatibility, RefusesAnotherCxxLibraryReleaseOrStringAbi) {
  auto plugin = this_build();
  std::strcpy(plugin.cxx_library, "libc++");
  plugin.cxx_library_version = 160000;
  EXPECT_NE(refusal(plugin).find(": another C++ library (libc++ 160000, netmc "), std::string::npos) << refusal(plugin);
  plugin = this_build();
  plugin.cxx_library_version += 1;
  EXPECT_NE(refusal(plugin).find(": another C++ library ("), std::string::npos) << refusal(plugin);
  plugin = this_build();
  plugin.cxx_string_abi = plugin.cxx_string_abi ? 0 : 1;
  EXPECT_NE(refusal(plugin).find(": another C++ library ("), std::string::npos) << refusal(plugin);
#if defined(_GLIBCXX_RELEASE)
  plugin = this_build();
  plugin.cxx_string_abi = 0;
  EXPECT_NE(refusal(plugin).find("(libstdc++ " + std::to_string(_GLIBCXX_RELEASE) +
                                 " with the pre-C++11 std::string, netmc libstdc++ " + std::to_string(_GLIBCXX_RELEASE) +
                                 " with the C++11 std::string)"),
            std::string::npos)
      << refusal(plugin);
#endif
}

TEST(ComponentPluginCompatibility, RefusesAnotherCxxStandard) {
  auto plugin = this_build();
  plugin.cplusplus = 201703;
  EXPECT_NE(refusal(plugin).find(": another C++ standard (__cplusplus 201703, netmc " + std::to_string(__cplusplus) + ")"),
            std::string::npos)
      << refusal(plugin);
}

TEST(ComponentPluginCompatibility, RefusesInterfacesOfAnotherSize) {
  auto plugin = this_build();
  plugin.axis_controller_size += 8;
  EXPECT_NE(refusal(plugin).find(": sizeof(netmc::control::AxisController) is " +
                                 std::to_string(sizeof(control::AxisController) + 8) + " bytes in the plugin, " +
                                 std::to_string(sizeof(control::AxisController)) + " in netmc"),
            std::string::npos)
      << refusal(plugin);
  plugin = this_build();
  plugin.axis_plant_size += 8;
  EXPECT_NE(refusal(plugin).find(": sizeof(netmc::plant::AxisPlant) is "), std::string::npos) << refusal(plugin);
  plugin = this_build();
  plugin.settings_size += 8;
  EXPECT_NE(refusal(plugin).find(": sizeof(netmc::control::ComponentSettings) is "), std::string::npos)
      << refusal(plugin);
  plugin = this_build();
  plugin.string_size += 8;
  EXPECT_NE(refusal(plugin).find(": sizeof(std::string) is "), std::string::npos) << refusal(plugin);
}

TEST(ComponentPluginCompatibility, ShowsThePluginsTextFieldsWithinBoundsAndPrintable) {
  auto plugin = this_build();
  std::memset(plugin.netmc_version, 'v', sizeof plugin.netmc_version);  // no NUL at all
  plugin.netmc_version[0] = '\x1b';
  const std::string message = refusal(plugin);
  EXPECT_EQ(message.rfind("plugin libx.so was built against netmc ?" + std::string(sizeof plugin.netmc_version - 1, 'v') +
                              " (plugin ABI 1, ",
                          0),
            0u)
      << message;
}

}  // namespace
}  // namespace netmc::plugins
