#include "server/drive/axis_limits.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace netmc::drive {
namespace {

void require_positive(double value, const char* flag) {
  if (!(value > 0.0)) {
    throw std::invalid_argument(std::string(flag) + ": expected a positive number");
  }
}

}  // namespace

void AxisLimits::validate() const {
  require_positive(command, "--command-limit");
  require_positive(velocity_m_s, "--velocity-limit");
  require_positive(slew_per_s, "--slew-limit");
  require_positive(following_error_m, "--following-error-limit");
  if (!(position_min_m < position_max_m) || std::isnan(position_min_m) || std::isnan(position_max_m)) {
    throw std::invalid_argument("--position-window: expected MIN:MAX in metres with MIN < MAX");
  }
}

bool AxisLimits::any() const {
  return std::isfinite(command) || std::isfinite(position_min_m) || std::isfinite(position_max_m) ||
         std::isfinite(velocity_m_s) || std::isfinite(slew_per_s) || std::isfinite(following_error_m);
}

AxisLimits AxisLimits::or_else(const AxisLimits& fallback) const {
  const auto pick = [](double own, double other) { return std::isinf(own) ? other : own; };
  AxisLimits out;
  out.command = pick(command, fallback.command);
  out.position_min_m = pick(position_min_m, fallback.position_min_m);
  out.position_max_m = pick(position_max_m, fallback.position_max_m);
  out.velocity_m_s = pick(velocity_m_s, fallback.velocity_m_s);
  out.slew_per_s = pick(slew_per_s, fallback.slew_per_s);
  out.following_error_m = pick(following_error_m, fallback.following_error_m);
  return out;
}

AxisLimits AxisLimits::with_default_following_error() const {
  AxisLimits out = *this;
  if (std::isinf(out.following_error_m)) out.following_error_m = default_following_error_m(*this);
  return out;
}

double default_following_error_m(const AxisLimits& limits) {
  constexpr double kWindowFraction = 0.1, kTravelTimeS = 0.1, kFloorM = 1e-3;
  const double window = limits.position_max_m - limits.position_min_m;
  if (!std::isfinite(window) || !std::isfinite(limits.velocity_m_s)) return std::numeric_limits<double>::infinity();
  return std::max(kFloorM, std::min(kWindowFraction * window, kTravelTimeS * limits.velocity_m_s));
}

std::string AxisLimits::describe() const {
  if (!any()) return "none";
  std::ostringstream text;
  const char* separator = "";
  if (std::isfinite(command)) {
    text << "command " << command;
    separator = ", ";
  }
  if (std::isfinite(position_min_m) || std::isfinite(position_max_m)) {
    text << separator << "position [" << position_min_m << ", " << position_max_m << "] m";
    separator = ", ";
  }
  if (std::isfinite(velocity_m_s)) {
    text << separator << "velocity " << velocity_m_s << " m/s";
    separator = ", ";
  }
  if (std::isfinite(slew_per_s)) {
    text << separator << "slew " << slew_per_s << "/s";
    separator = ", ";
  }
  if (std::isfinite(following_error_m)) text << separator << "following error " << following_error_m * 1e3 << " mm";
  return text.str();
}

}  // namespace netmc::drive
