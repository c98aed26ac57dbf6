// Progress on stderr: a plain line per 10 % when not on a terminal, the final line with the
// elapsed time, nothing when quiet; durations as people read them.
#include <gtest/gtest.h>

#include <sstream>
#include <thread>

#include "client/progress_bar.hpp"

namespace netmc::cli {
namespace {

TEST(ProgressBar, LinesStyleWritesOneLinePerTenPercentAndAFinalOne) {
  std::ostringstream out;
  ProgressBar progress(200, "iterations", ProgressBar::Style::lines, out);
  std::vector<std::thread> workers;
  for (int t = 0; t < 4; ++t) {
    workers.emplace_back([&] {
      for (int i = 0; i < 50; ++i) progress.advance();
    });
  }
  for (auto& worker : workers) worker.join();
  progress.finish();
  const std::string text = out.str();
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 10) << text;  // 10 % ... 90 %, then done
  EXPECT_NE(text.find("progress:  10%  20/200 iterations"), std::string::npos) << text;
  EXPECT_NE(text.find("progress:  90%  180/200 iterations"), std::string::npos) << text;
  EXPECT_NE(text.find("progress: 100%  200/200 iterations  in "), std::string::npos) << text;
}

TEST(ProgressBar, FinishCountsRunsThatStoppedEarlyAndOffPrintsNothing) {
  std::ostringstream out;
  ProgressBar progress(100, "iterations", ProgressBar::Style::bar, out);
  for (int i = 0; i < 40; ++i) progress.advance();
  progress.finish();
  EXPECT_NE(out.str().find("[##############################] 100%  100/100 iterations  in "),
            std::string::npos)
      << out.str();
  std::ostringstream quiet;
  ProgressBar off(100, "iterations", ProgressBar::Style::off, quiet);
  off.advance(50);
  off.finish();
  EXPECT_EQ(quiet.str(), "");
}

TEST(ProgressBar, Durations) {
  EXPECT_EQ(ProgressBar::format_duration(3.24), "3.2s");
  EXPECT_EQ(ProgressBar::format_duration(42.4), "42s");
  EXPECT_EQ(ProgressBar::format_duration(65.0), "1m05s");
  EXPECT_EQ(ProgressBar::format_duration(7322.0), "2h02m");
  EXPECT_EQ(ProgressBar::format_duration(-1.0), "?");
}

}  // namespace
}  // namespace netmc::cli
