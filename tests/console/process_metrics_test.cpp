// The process metrics against a /proc/PID/stat line written by hand (a command name with spaces
// and parentheses, which a split on spaces would misread) and against this test's own process.
#include <gtest/gtest.h>

#include <chrono>
#include <string>

#include "server/console/process_metrics.hpp"

namespace netmc::console {
namespace {

TEST(ProcessMetrics, ReadsTheStatFieldsAfterTheCommandsLastParenthesis) {
  // Fields 3..24: state ppid pgrp session tty tpgid flags minflt cminflt majflt cmajflt utime
  // stime cutime cstime priority nice threads itrealvalue starttime vsize rss.
  const std::string line = "42 (we ird) x) S 1 42 42 0 -1 4194560 10 0 0 0 250 150 7 9 20 0 3 0 1000 8192000 300 "
                           "18446744073709551615 1 1 0 0 0 0 0 0 0 0 0 17 1 0 0 0 0 0";
  const auto m = parse_proc_stat(line, 100.0, 4096.0, 1.7e9);
  ASSERT_TRUE(m);
  EXPECT_DOUBLE_EQ(m->cpu_seconds, 4.0);  // (250 + 150) / 100: own time only, not the children's
  EXPECT_DOUBLE_EQ(m->start_time_unix_s, 1.7e9 + 10.0);
  EXPECT_DOUBLE_EQ(m->virtual_bytes, 8192000.0);
  EXPECT_DOUBLE_EQ(m->resident_bytes, 300.0 * 4096.0);
  EXPECT_FALSE(parse_proc_stat("42 (cut) S 1 2 3", 100.0, 4096.0, 0.0));
  EXPECT_FALSE(parse_proc_stat("no parenthesis at all", 100.0, 4096.0, 0.0));
  EXPECT_FALSE(parse_proc_stat(line, 0.0, 4096.0, 0.0));
}

TEST(ProcessMetrics, ThisProcessHasMemoryFilesAndAStartInThePast) {
  const auto m = read_process_metrics();
  ASSERT_TRUE(m);
  const double now = std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
  EXPECT_GT(m->resident_bytes, 1e5);
  EXPECT_GE(m->virtual_bytes, m->resident_bytes);
  EXPECT_GE(m->cpu_seconds, 0.0);
  EXPECT_LE(m->start_time_unix_s, now + 1.0);
  EXPECT_GT(m->start_time_unix_s, now - 3600.0);  // started by this test run
  EXPECT_GE(m->open_fds, 3.0);                    // stdin, stdout, stderr
  EXPECT_GE(m->max_fds, m->open_fds);
}

}  // namespace
}  // namespace netmc::console
