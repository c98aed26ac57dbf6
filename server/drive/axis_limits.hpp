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
  // |x_ref - x| during a job's iterations: the job's reference for this axis at the sample's
  // instant minus the measured position (default_following_error_m when the operator gives none).
  double following_error_m = std::numeric_limits<double>::infinity();

  // Throws std::invalid_argument naming the limit (as its flag) for a non-positive or NaN limit
  // or an empty window.
  void validate() const;
  bool any() const;
  // Each limit of `fallback` where this one has none (infinite).
  AxisLimits or_else(const AxisLimits& fallback) const;
  std::string describe() const;  // "command 5, position [-0.1, 0.2] m, ..." or "none"
  // This one with following_error_m set to default_following_error_m() where it has none.
  AxisLimits with_default_following_error() const;
};

// The following-error limit of an axis whose operator set none: a tenth of its travel window,
// at most the distance it covers in 0.1 s at its velocity limit, at least 1 mm; infinity (none)
// unless both the window and the velocity limit are finite. Why these bounds:
// - a tenth of the travel: an error that large is a runaway or a wrong axis, not tracking;
// - V x 0.1 s: an axis that lags its reference by more than two watchdog periods (50 ms each) of
//   travel at its top speed is not following it;
// - 1 mm: ten times paper 001's tracking errors (~0.1 mm), and more than twice the 0.4 mm its
//   7.9 mm/s contour runs away from an axis during a 50 ms host stall.
double default_following_error_m(const AxisLimits& limits);

}  // namespace netmc::drive
