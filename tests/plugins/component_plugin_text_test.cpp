// Text from a plugin: never read past its bounds, printable ASCII only, trimmed, cut short.
#include "server/plugins/component_plugin_text.hpp"

#include <gtest/gtest.h>

#include <string>

namespace netmc::plugins {
namespace {

TEST(ComponentPluginText, StopsAtTheFirstNulOrTheEndOfTheField) {
  const char field[8] = {'0', '.', '1', '\0', 'x', 'x', 'x', 'x'};
  EXPECT_EQ(plugin_text(field, sizeof field, "none"), "0.1");
  const char full[4] = {'a', 'b', 'c', 'd'};
  EXPECT_EQ(plugin_text(full, sizeof full, "none"), "abcd");
}

TEST(ComponentPluginText, ShowsControlAndNonAsciiBytesAsQuestionMarks) {
  EXPECT_EQ(plugin_text("\x1b[2Jwiped\r\nkp \xc3\xa9", "none"), "?[2Jwiped??kp ??");
}

TEST(ComponentPluginText, TrimsFallsBackAndCutsLongText) {
  EXPECT_EQ(plugin_text("  kp  ", "none"), "kp");
  EXPECT_EQ(plugin_text("   ", "none"), "none");
  EXPECT_EQ(plugin_text(std::string(kMaxPluginTextLength, 'x'), "none"), std::string(kMaxPluginTextLength, 'x'));
  EXPECT_EQ(plugin_text(std::string(kMaxPluginTextLength + 1, 'x'), "none"),
            std::string(kMaxPluginTextLength, 'x') + "...");
}

}  // namespace
}  // namespace netmc::plugins
