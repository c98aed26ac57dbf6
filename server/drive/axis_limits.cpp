#include "server/drive/axis_limits.hpp"

#include <cmath>
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
  if (!(position_min_m < position_max_m) || std::isnan(position_min_m) || std::isnan(position_max_m)) {
    throw std::invalid_argument("--position-window: expected MIN:MAX in metres with MIN < MAX");
  }
}

bool AxisLimits::any() const {
  return std::isfinite(command) || std::isfinite(position_min_m) || std::isfinite(position_max_m) ||
         std::isfinite(velocity_m_s) || std::isfinite(slew_per_s);
}

AxisLimits AxisLimits::or_else(const AxisLimits& fallback) const {
  const auto pick = [](double own, double other) { return std::isinf(own) ? other : own; };
  AxisLimits out;
  out.command = pick(command, fallback.command);
  out.position_min_m = pick(position_min_m, fallback.position_min_m);
  out.position_max_m = pick(position_max_m, fallback.position_max_m);
  out.velocity_m_s = pick(velocity_m_s, fallback.velocity_m_s);
  out.slew_per_s = pick(slew_per_s, fallback.slew_per_s);
  return out;
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
  if (std::isfinite(slew_per_s)) text << separator << "slew " << slew_per_s << "/s";
  return text.str();
}

}  // namespace netmc::drive
