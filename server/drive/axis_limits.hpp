#pragma once
// The limits an axis's operator sets on the axis itself (netmc-axis flags), enforced at the
// actuator whatever any server sends: a command the drive must not take, a position outside the
// machine's travel or a velocity beyond its rating trips the axis into a latched fault (the
// drive's quick stop brings it to standstill, then CiA 402 Fault) instead of reaching the plant.
// A job's command_limit, by contrast, is part of the plant model (drive saturation) and clamps.

#include <limits>
#include <string>

namespace netmc::drive {

struct AxisLimits {
  double command = std::numeric_limits<double>::infinity();         // |U|, the plant's input unit
  double position_min_m = -std::numeric_limits<double>::infinity();  // travel window
  double position_max_m = std::numeric_limits<double>::infinity();
  double velocity_m_s = std::numeric_limits<double>::infinity();     // |x'|
  // |dU/dt|: a new command moves the applied one by at most this per second since the last
  // change (units of U per second).
  double slew_per_s = std::numeric_limits<double>::infinity();

  // Throws std::invalid_argument naming the limit (as its flag) for a non-positive or NaN limit
  // or an empty window.
  void validate() const;
  bool any() const;
  // Each limit of `fallback` where this one has none (infinite).
  AxisLimits or_else(const AxisLimits& fallback) const;
  std::string describe() const;  // "command 5, position [-0.1, 0.2] m, ..." or "none"
};

}  // namespace netmc::drive
