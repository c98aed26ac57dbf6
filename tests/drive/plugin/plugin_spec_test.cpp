// The text after `plugin:`: the path, then key=value pairs, every part checked and bounded.
#include "server/drive/plugin/plugin_spec.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace netmc::drive {
namespace {

std::string refusal(const std::string& text) {
  try {
    parse_plugin_spec(text);
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  return "";
}

TEST(PluginSpec, APathAlone) {
  const PluginSpec spec = parse_plugin_spec("/opt/lab/libsoem_drive.so");
  EXPECT_EQ(spec.path, "/opt/lab/libsoem_drive.so");
  EXPECT_TRUE(spec.settings.empty());
}

TEST(PluginSpec, APathAndItsSettingsInOrderValuesMayHoldColonsAndEquals) {
  const PluginSpec spec = parse_plugin_spec("./libdrive.so:ifname=eth0,slave.1-gain_x=2.5,uri=tcp://a:1502/x=y,note=");
  EXPECT_EQ(spec.path, "./libdrive.so");
  ASSERT_EQ(spec.settings.size(), 4u);
  EXPECT_EQ(spec.settings[0], std::make_pair(std::string("ifname"), std::string("eth0")));
  EXPECT_EQ(spec.settings[1], std::make_pair(std::string("slave.1-gain_x"), std::string("2.5")));
  EXPECT_EQ(spec.settings[2], std::make_pair(std::string("uri"), std::string("tcp://a:1502/x=y")));
  EXPECT_EQ(spec.settings[3], std::make_pair(std::string("note"), std::string("")));
}

TEST(PluginSpec, RefusesEachMalformedPart) {
  EXPECT_EQ(refusal(""), "--drive plugin: no path to the plugin (plugin:PATH.so[:key=value,...])");
  EXPECT_EQ(refusal(":a=1"), "--drive plugin: no path to the plugin (plugin:PATH.so[:key=value,...])");
  EXPECT_EQ(refusal("x.so:"), "--drive plugin: an empty key=value item (two commas, or a comma at an end)");
  EXPECT_EQ(refusal("x.so:a=1,,b=2"), "--drive plugin: an empty key=value item (two commas, or a comma at an end)");
  EXPECT_EQ(refusal("x.so:a=1,"), "--drive plugin: an empty key=value item (two commas, or a comma at an end)");
  EXPECT_EQ(refusal("x.so:gain"), "--drive plugin: 'gain' has no '=' (settings are key=value)");
  EXPECT_EQ(refusal("x.so:=1"), "--drive plugin: '=1' has no key before '='");
  EXPECT_EQ(refusal("x.so:a b=1"), "--drive plugin: key 'a b' has a character other than A-Z a-z 0-9 _ . -");
  EXPECT_EQ(refusal("x.so:a=1,a=2"), "--drive plugin: key a given twice");
  EXPECT_EQ(refusal("x.so:a=\t1"), "--drive plugin: the value of a has a character that is not printable ASCII");
  EXPECT_EQ(refusal("x\n.so"), "--drive plugin: the path has a character that is not printable ASCII");
}

TEST(PluginSpec, BoundsEveryLength) {
  EXPECT_EQ(refusal("x.so:" + std::string(kMaxPluginKeyLength, 'k') + "=1"), "");
  EXPECT_NE(refusal("x.so:" + std::string(kMaxPluginKeyLength + 1, 'k') + "=1").find("longer than 64 characters"),
            std::string::npos);
  EXPECT_EQ(refusal("x.so:k=" + std::string(kMaxPluginValueLength, 'v')), "");
  EXPECT_EQ(refusal("x.so:k=" + std::string(kMaxPluginValueLength + 1, 'v')),
            "--drive plugin: the value of k is longer than 256 characters");
  EXPECT_EQ(refusal("/" + std::string(kMaxPluginPathLength, 'p')),
            "--drive plugin: the path is longer than 4096 characters");
  std::string many = "x.so:";
  for (std::size_t i = 0; i < kMaxPluginSettings; ++i) many += (i ? ",k" : "k") + std::to_string(i) + "=1";
  EXPECT_EQ(parse_plugin_spec(many).settings.size(), kMaxPluginSettings);
  EXPECT_EQ(refusal(many + ",one=more"), "--drive plugin: more than 64 key=value settings");
}

}  // namespace
}  // namespace netmc::drive
