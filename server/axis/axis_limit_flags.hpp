#pragma once
// The operator's limits of a node's axes, from netmc-axis's flags. Each flag takes a VALUE for
// every axis, or comma-separated entries AXIS=VALUE; an entry without AXIS sets every axis and
// later entries override earlier ones: --position-window=-0.05:0.25,stage1.y=0:0.45 gives
// stage1.y its own travel and every other axis of the node [-0.05, 0.25] m.

#include <map>
#include <string>
#include <vector>

#include "server/drive/axis_limits.hpp"

namespace netmc::axis {

struct AxisLimitFlags {
  std::string command;          // --command-limit U
  std::string position_window;  // --position-window MIN:MAX (m)
  std::string velocity;         // --velocity-limit V (m/s)
  std::string slew;             // --slew-limit R (units/s)
  std::string following_error;  // --following-error-limit LENGTH (2mm, 0.002)
};

// The limits of each of `axes` (an axis no flag names has none). Throws std::invalid_argument
// naming the flag, the axis and the expected form, for an axis the node does not host, a value
// that is not a finite number (a window with MIN < MAX) or a limit that is not positive.
std::map<std::string, drive::AxisLimits> parse_axis_limits(const AxisLimitFlags& flags,
                                                         const std::vector<std::string>& axes);

// "x: command 8, position [-0.05, 0.25] m; y: none", in the order of `axes`.
std::string describe_axis_limits(const std::map<std::string, drive::AxisLimits>& limits,
                                 const std::vector<std::string>& axes);

}  // namespace netmc::axis
