#pragma once
// The axis-node side of one axis in virtual time: a plant, its position sensor, and the
// event-driven actuator. A setpoint acts from the instant it arrives (paper 001, eq. 2/4: during
// [t_k, t_k + tau) the previous input still acts); late setpoints older than the one in force are
// dropped by sequence number; a lost setpoint leaves the last input in force.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "netsim/delayed_channel.hpp"
#include "netsim/freshness_filter.hpp"
#include "plant/axis_plant.hpp"
#include "plant/position_sensor.hpp"
#include "server/sim/axis_limits.hpp"

namespace netmc::sim {

class SimulatedAxis {
 public:
  using Delivery = netsim::DelayedChannel<double>::Delivery;

  // `command_limit`: the job's drive saturation (clamps); `limits`: the axis operator's (trip).
  SimulatedAxis(std::unique_ptr<plant::AxisPlant> plant, plant::PositionSensor sensor,
                double command_limit, AxisLimits limits = {});

  // Back to rest at `position` for a new iteration; a latched fault stays (only the operator
  // clears it, see clear_fault).
  void reset(double position);
  // Watchdog: no setpoint in time, so the drive is commanded to stand still.
  void hold() { input_ = 0.0; }
  double measure();                                  // sampled position at the current time
  // Integrate to `end_time_s` applying the setpoints delivered in (now, end] in arrival order.
  void advance_to(double end_time_s, const std::vector<Delivery>& deliveries);

  const plant::AxisPlant& plant() const { return *plant_; }
  double input() const { return input_; }
  // Why the axis tripped (the first reason), nullopt while it is healthy. A faulted axis
  // applies no command: its input stays zero.
  const std::optional<std::string>& fault() const { return fault_; }
  void clear_fault() { fault_.reset(); }
  std::uint64_t stale_setpoints() const { return freshness_.stale_dropped(); }

 private:
  std::unique_ptr<plant::AxisPlant> plant_;
  plant::PositionSensor sensor_;
  netsim::FreshnessFilter freshness_;
  double command_limit_;
  AxisLimits limits_;
  double input_ = 0.0;
  double time_s_ = 0.0;
  double input_changed_s_ = 0.0;  // when the applied input last changed (slew limit)
  std::optional<std::string> fault_;

  void trip(const std::string& reason);  // latches the first reason, commands zero
  void check_state();                    // trips on a position or velocity beyond the limits
};

}  // namespace netmc::sim
