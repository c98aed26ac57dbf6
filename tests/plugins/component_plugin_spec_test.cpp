// The text after `plugin:` for a component plugin: the path, then key=number pairs, every part
// checked and bounded, each refusal one message naming the key or the part.
#include "server/plugins/component_plugin_spec.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace netmc::plugins {
namespace {

std::string refusal(const std::string& text) {
  try {
    parse_component_plugin_spec(text);
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  return "";
}

TEST(ComponentPluginSpec, APathAlone) {
  const ComponentPluginSpec spec = parse_component_plugin_spec("/opt/lab/libmy_law.so");
  EXPECT_EQ(spec.path, "/opt/lab/libmy_law.so");
  EXPECT_TRUE(spec.settings.empty());
}

TEST(ComponentPluginSpec, APathAndItsNumericSettings) {
  const ComponentPluginSpec spec =
      parse_component_plugin_spec("./libpd.so:kp=400,kd=40.5,axis.y-gain_2=-1.5e-3,offset=+2,tiny=.5,big=1E3");
  EXPECT_EQ(spec.path, "./libpd.so");
  const PluginSettings expected = {{"kp", 400.0},          {"kd", 40.5}, {"axis.y-gain_2", -1.5e-3},
                                   {"offset", 2.0},        {"tiny", 0.5}, {"big", 1000.0}};
  EXPECT_EQ(spec.settings, expected);
}

TEST(ComponentPluginSpec, RefusesEachMalformedPart) {
  EXPECT_EQ(refusal(""), "plugin: no path to the plugin (plugin:PATH.so[:key=value,...])");
  EXPECT_EQ(refusal(":kp=1"), "plugin: no path to the plugin (plugin:PATH.so[:key=value,...])");
  EXPECT_EQ(refusal("lib,x.so:kp=1"), "plugin: the path 'lib,x.so' has a ',' (a plugin's path may hold neither ':' nor ',')");
  EXPECT_EQ(refusal("x\n.so"), "plugin: the path has a character that is not printable ASCII");
  EXPECT_EQ(refusal("x.so:"), "plugin: an empty key=value item (two commas, or a comma at an end)");
  EXPECT_EQ(refusal("x.so:kp=1,,kd=2"), "plugin: an empty key=value item (two commas, or a comma at an end)");
  EXPECT_EQ(refusal("x.so:kp=1,"), "plugin: an empty key=value item (two commas, or a comma at an end)");
  EXPECT_EQ(refusal("x.so:kp"), "plugin: 'kp' has no '=' (settings are key=value)");
  EXPECT_EQ(refusal("x.so:=1"), "plugin: '=1' has no key before '='");
  EXPECT_EQ(refusal("x.so:k p=1"), "plugin: key 'k p' has a character other than A-Z a-z 0-9 _ . -");
  EXPECT_EQ(refusal("x.so:kp=1,kp=2"), "plugin: key kp given twice");
  EXPECT_EQ(refusal("x.so:kp="), "plugin: key kp has no value (settings are key=number)");
  // The path ends at the first ':', so a second one lands in the settings.
  EXPECT_EQ(refusal("/a:b/x.so"), "plugin: 'b/x.so' has no '=' (settings are key=value)");
}

TEST(ComponentPluginSpec, TakesFiniteDecimalNumbersOnly) {
  for (const char* value : {"fast", "inf", "-inf", "nan", "0x10", "1e999", "1.5.2", "--1", "+-1", "1e", "."}) {
    EXPECT_EQ(refusal(std::string("x.so:kp=") + value),
              std::string("plugin: the value of kp, '") + value + "', is not a finite decimal number")
        << value;
  }
  EXPECT_EQ(refusal("x.so:kp=\t1"), "plugin: the value of kp, '?1', is not a finite decimal number");
  EXPECT_EQ(parse_component_plugin_spec("x.so:kp=-0").settings.at("kp"), 0.0);
}

TEST(ComponentPluginSpec, BoundsEveryLength) {
  EXPECT_EQ(refusal("x.so:" + std::string(kMaxComponentPluginKeyLength, 'k') + "=1"), "");
  EXPECT_EQ(refusal("x.so:" + std::string(kMaxComponentPluginKeyLength + 1, 'k') + "=1"),
            "plugin: key '" + std::string(kMaxComponentPluginKeyLength + 1, 'k') + "' is longer than 64 characters");
  EXPECT_EQ(refusal("x.so:k=" + std::string(kMaxComponentPluginValueLength, '1')), "");
  EXPECT_EQ(refusal("x.so:k=" + std::string(kMaxComponentPluginValueLength + 1, '1')),
            "plugin: the value of k is longer than 64 characters");
  EXPECT_EQ(refusal("/" + std::string(kMaxComponentPluginPathLength, 'p')),
            "plugin: the path is longer than 4096 characters");
  std::string many = "x.so:";
  for (std::size_t i = 0; i < kMaxComponentPluginSettings; ++i) {
    many += i ? ",k" : "k";
    many += std::to_string(i);
    many += "=1";
  }
  EXPECT_EQ(parse_component_plugin_spec(many).settings.size(), kMaxComponentPluginSettings);
  EXPECT_EQ(refusal(many + ",one=2"), "plugin: more than 64 key=value settings");
}

TEST(ComponentPluginSpec, KeysAsTheSpecTakesThem) {
  EXPECT_TRUE(is_component_plugin_key("a2"));
  EXPECT_TRUE(is_component_plugin_key("x.y-z_0"));
  EXPECT_FALSE(is_component_plugin_key(""));
  EXPECT_FALSE(is_component_plugin_key("a=b"));
  EXPECT_FALSE(is_component_plugin_key(std::string(kMaxComponentPluginKeyLength + 1, 'k')));
}

}  // namespace
}  // namespace netmc::plugins
