#pragma once
// Progress of a long run on stderr: a redrawn bar with ETA on a terminal, a plain line per 10 %
// otherwise (logs, CI), nothing when quiet. Thread-safe: workers call advance().

#include <chrono>
#include <cstddef>
#include <iosfwd>
#include <mutex>
#include <string>

namespace netmc::cli {

class ProgressBar {
 public:
  enum class Style { bar, lines, off };

  // `unit` names what is counted ("iterations").
  ProgressBar(std::size_t total, std::string unit, Style style, std::ostream& out);
  // Style for stderr: bar on a terminal, lines otherwise, off when quiet.
  static Style style_for_stderr(bool quiet);

  void advance(std::size_t count = 1);
  // Draws the final state and ends the line.
  void finish();

  // "1m05s", "42s", "3.2s".
  static std::string format_duration(double seconds);

 private:
  void draw(bool final);

  std::size_t total_;
  std::string unit_;
  Style style_;
  std::ostream& out_;
  std::mutex mutex_;
  std::size_t done_ = 0;
  std::size_t next_line_percent_ = 10;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_draw_;
  bool finished_ = false;
};

}  // namespace netmc::cli
