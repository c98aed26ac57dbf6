#include "client/progress_bar.hpp"

#include <fmt/format.h>
#include <fmt/ostream.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <ostream>

namespace netmc::cli {
namespace {

constexpr int kBarWidth = 30;
constexpr auto kRedrawInterval = std::chrono::milliseconds(100);

}  // namespace

ProgressBar::ProgressBar(std::size_t total, std::string unit, Style style, std::ostream& out)
    : total_(std::max<std::size_t>(total, 1)),
      unit_(std::move(unit)),
      style_(style),
      out_(out),
      start_(std::chrono::steady_clock::now()),
      last_draw_(start_) {}

ProgressBar::Style ProgressBar::style_for_stderr(bool quiet) {
  if (quiet) return Style::off;
  return isatty(STDERR_FILENO) ? Style::bar : Style::lines;
}

std::string ProgressBar::format_duration(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0.0) return "?";
  if (seconds < 10.0) return fmt::format("{:.1f}s", seconds);
  const auto whole = static_cast<long long>(std::lround(seconds));
  if (whole < 60) return fmt::format("{}s", whole);
  if (whole < 3600) return fmt::format("{}m{:02}s", whole / 60, whole % 60);
  return fmt::format("{}h{:02}m", whole / 3600, (whole % 3600) / 60);
}

void ProgressBar::advance(std::size_t count) {
  if (style_ == Style::off) return;
  const std::lock_guard lock(mutex_);
  done_ = std::min(total_, done_ + count);
  const auto now = std::chrono::steady_clock::now();
  if (style_ == Style::bar) {
    if (now - last_draw_ < kRedrawInterval && done_ < total_) return;
    last_draw_ = now;
    draw(false);
  } else if (done_ * 100 >= next_line_percent_ * total_ && done_ < total_) {
    draw(false);
    while (done_ * 100 >= next_line_percent_ * total_) next_line_percent_ += 10;
  }
}

void ProgressBar::finish() {
  if (style_ == Style::off) return;
  const std::lock_guard lock(mutex_);
  if (finished_) return;
  finished_ = true;
  done_ = total_;  // runs that stop early (unstable) leave planned iterations uncounted
  draw(true);
}

void ProgressBar::draw(bool final) {
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double fraction = static_cast<double>(done_) / static_cast<double>(total_);
  const double eta = done_ == 0 ? -1.0 : elapsed * (1.0 - fraction) / fraction;
  const std::string timing = final ? fmt::format("in {}", format_duration(elapsed))
                                   : fmt::format("elapsed {}, ETA {}", format_duration(elapsed),
                                                 format_duration(eta));
  if (style_ == Style::bar) {
    const int filled = static_cast<int>(fraction * kBarWidth);
    fmt::print(out_, "\r[{}{}] {:3.0f}%  {}/{} {}  {}\x1b[K", std::string(static_cast<std::size_t>(filled), '#'),
               std::string(static_cast<std::size_t>(kBarWidth - filled), '.'), fraction * 100.0, done_,
               total_, unit_, timing);
    if (final) fmt::print(out_, "\n");
  } else {
    fmt::print(out_, "progress: {:3.0f}%  {}/{} {}  {}\n", fraction * 100.0, done_, total_, unit_, timing);
  }
  out_.flush();
}

}  // namespace netmc::cli
