#pragma once
// The axis-node side of one axis in virtual time, as netmc-axis runs it: the simulated axis
// (plant, sensor, event-driven actuator, limits) behind its downlink, where netsim delays or
// drops each setpoint before the axis applies it. In-process runs call it directly; the
// distributed lockstep run calls the same code inside netmc-axis.

#include <cstdint>
#include <memory>
#include <vector>

#include "netsim/delayed_channel.hpp"
#include "server/sim/contour_job.hpp"
#include "server/sim/simulated_axis.hpp"

namespace netmc::sim {

struct AxisSample {
  double measured_m = 0.0;        // what the sensor reports
  double true_position_m = 0.0;   // the plant's state, for ground-truth metrics only
};

// A setpoint that reached the actuator: for the loop-delay statistics.
struct AppliedSetpoint {
  std::uint64_t sequence = 0;
  double send_time_s = 0.0;
  double arrival_time_s = 0.0;
};

class AxisEndpoint {
 public:
  // Axis `axis` (its place in the group) of `job`, under its operator's `limits` (none in-process).
  AxisEndpoint(std::unique_ptr<plant::AxisPlant> plant, const ContourJob& job, std::size_t axis,
               AxisLimits limits = {});

  // Every iteration starts from rest at `start_position_m` with nothing in flight.
  void begin_iteration(std::size_t iteration, double start_position_m);
  AxisSample sample();
  // Setpoint `sequence` leaves the server at `send_time_s`; false if the downlink drops it.
  bool submit_setpoint(double send_time_s, std::uint64_t sequence, double command);
  // Integrate to `end_time_s`, applying the setpoints that arrive on the way; the result is
  // valid until the next call (one buffer, no allocation per cycle).
  const std::vector<AppliedSetpoint>& advance_to(double end_time_s);

  void hold() { axis_.hold(); }
  // The operator's limits tripped (SimulatedAxis::fault); a node reports it and stops.
  const std::optional<std::string>& fault() const { return axis_.fault(); }

  std::uint64_t lost_setpoints() const { return lost_; }
  std::uint64_t stale_setpoints() const { return axis_.stale_setpoints(); }

 private:
  SimulatedAxis axis_;
  netsim::DelayedChannel<double> downlink_;
  std::vector<netsim::DelayedChannel<double>::Delivery> deliveries_;
  std::vector<AppliedSetpoint> applied_;
  std::uint64_t seed_;
  std::size_t index_;
  std::uint64_t lost_ = 0;
};

}  // namespace netmc::sim
