// Text from a plugin's buffer: never read past the buffer, printable ASCII only, trimmed.
#include "server/drive/plugin/plugin_text.hpp"

#include <gtest/gtest.h>

#include <string>

namespace netmc::drive {
namespace {

TEST(PluginText, StopsAtTheFirstNul) {
  const char buffer[16] = "cycle\0 later";
  EXPECT_EQ(plugin_text(buffer, sizeof buffer, "none"), "cycle");
}

TEST(PluginText, StopsAtTheBuffersEndWithoutANul) {
  const char buffer[4] = {'a', 'b', 'c', 'd'};
  EXPECT_EQ(plugin_text(buffer, sizeof buffer, "none"), "abcd");
}

TEST(PluginText, ShowsControlAndNonAsciiBytesAsQuestionMarks) {
  const char buffer[] = "\x1b[2Jwiped\r\nslave \xc3\xa9";
  EXPECT_EQ(plugin_text(buffer, sizeof buffer, "none"), "?[2Jwiped??slave ??");
}

TEST(PluginText, TrimsBlanksAndFallsBackWhenNothingIsLeft) {
  const char padded[] = "  timeout  ";
  EXPECT_EQ(plugin_text(padded, sizeof padded, "none"), "timeout");
  const char blank[] = "   ";
  EXPECT_EQ(plugin_text(blank, sizeof blank, "none"), "none");
  EXPECT_EQ(plugin_text(blank, 0, "none"), "none");
}

}  // namespace
}  // namespace netmc::drive
