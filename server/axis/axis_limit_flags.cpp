#include "server/axis/axis_limit_flags.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>

#include "server/drive/drive_spec.hpp"
#include "server/job/quantity_text.hpp"

namespace netmc::axis {
namespace {

// Applies `set(limits, value text)` to the axes each entry of `text` names; `set` returns false
// for a value not of the flag's form.
void apply_flag(const std::string& text, const std::string& flag, const std::string& form,
                const std::vector<std::string>& axes, std::map<std::string, drive::AxisLimits>& limits,
                const std::function<bool(drive::AxisLimits&, const std::string&)>& set) {
  if (text.empty()) return;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    const std::string entry = text.substr(start, comma - start);
    const std::size_t equals = entry.find('=');
    const std::string axis = equals == std::string::npos ? "" : entry.substr(0, equals);
    const std::string value = equals == std::string::npos ? entry : entry.substr(equals + 1);
    const std::string where = axis.empty() ? "" : " (axis " + axis.substr(0, 64) + ")";
    if (equals != std::string::npos && !axis.empty() && std::find(axes.begin(), axes.end(), axis) == axes.end()) {
      throw std::invalid_argument(flag + ": '" + axis.substr(0, 64) + "' is not an axis of this node (--axes)");
    }
    const std::vector<std::string> targets = axis.empty() ? axes : std::vector<std::string>{axis};
    for (const auto& target : targets) {
      if (equals == 0 || !set(limits[target], value)) {
        throw std::invalid_argument(flag + where + ": expected " + form + " or AXIS=" + form +
                                    " entries separated by commas, got '" + entry.substr(0, 80) + "'");
      }
    }
    start = comma + 1;
  }
}

}  // namespace

std::map<std::string, drive::AxisLimits> parse_axis_limits(const AxisLimitFlags& flags,
                                                         const std::vector<std::string>& axes) {
  std::map<std::string, drive::AxisLimits> limits;
  for (const auto& axis : axes) limits[axis] = {};
  const auto positive = [](double drive::AxisLimits::*field) {
    return [field](drive::AxisLimits& target, const std::string& text) {
      double value = 0.0;
      if (!drive::parse_finite_decimal(text, value) || !(value > 0.0)) return false;
      target.*field = value;
      return true;
    };
  };
  apply_flag(flags.command, "--command-limit", "a positive number U", axes, limits,
             positive(&drive::AxisLimits::command));
  apply_flag(flags.velocity, "--velocity-limit", "a positive number V (m/s)", axes, limits,
             positive(&drive::AxisLimits::velocity_m_s));
  apply_flag(flags.slew, "--slew-limit", "a positive number R (units/s)", axes, limits,
             positive(&drive::AxisLimits::slew_per_s));
  apply_flag(flags.following_error, "--following-error-limit", "a positive length such as 2mm", axes, limits,
             [](drive::AxisLimits& target, const std::string& text) {
               try {
                 const double value = job::parse_quantity(text, job::Quantity::length, "--following-error-limit");
                 if (!(value > 0.0) || !std::isfinite(value)) return false;
                 target.following_error_m = value;
                 return true;
               } catch (const std::invalid_argument&) {
                 return false;
               }
             });
  apply_flag(flags.position_window, "--position-window", "MIN:MAX (m, MIN < MAX)", axes, limits,
             [](drive::AxisLimits& target, const std::string& text) {
               const std::size_t colon = text.find(':', 1);  // MIN may be negative
               double min = 0.0, max = 0.0;
               if (colon == std::string::npos || !drive::parse_finite_decimal(text.substr(0, colon), min) ||
                   !drive::parse_finite_decimal(text.substr(colon + 1), max) || !(min < max)) {
                 return false;
               }
               target.position_min_m = min;
               target.position_max_m = max;
               return true;
             });
  return limits;  // each entry checked as it was parsed (SimulatedAxis checks them once more)
}

std::string describe_axis_limits(const std::map<std::string, drive::AxisLimits>& limits,
                                 const std::vector<std::string>& axes) {
  std::string text;
  for (const auto& axis : axes) {
    const auto it = limits.find(axis);
    text += (text.empty() ? "" : "; ") + axis + ": " + (it == limits.end() ? "none" : it->second.describe());
  }
  return text;
}

}  // namespace netmc::axis
