#pragma once
// The axis-node side of one axis, as netmc-axis runs it and netmc sim calls it: the drive under
// its supervision (limits, trips, the CiA 402 master: drive::SupervisedAxis), the position sensor
// the job models on top of the drive's actual position, and the downlink on which netsim delays
// or drops each setpoint before the axis applies it. In-process runs call it directly with
// netmc's simulated drive; the distributed runs call the same code inside netmc-axis.

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "netsim/delayed_channel.hpp"
#include "plant/position_sensor.hpp"
#include "server/drive/supervised_axis.hpp"
#include "server/sim/contour_job.hpp"

namespace netmc::sim {

struct AxisSample {
  double measured_m = 0.0;        // what the sensor reports
  double true_position_m = 0.0;   // the drive's actual position (a simulation's: the plant's state)
};

// A setpoint that reached the actuator: for the loop-delay statistics.
struct AppliedSetpoint {
  std::uint64_t sequence = 0;
  double send_time_s = 0.0;
  double arrival_time_s = 0.0;
};

class AxisEndpoint {
 public:
  // Axis `axis` (its place in the group) of `job` on `drive`, under its operator's `limits`
  // (none in-process).
  AxisEndpoint(std::shared_ptr<drive::Drive> drive, const ContourJob& job, std::size_t axis,
               drive::AxisLimits limits = {});
  // netmc's simulated drive of the job's plant for axis `axis`.
  static std::shared_ptr<drive::Drive> simulated_drive(const ContourJob& job, std::size_t axis);

  // Every iteration starts from rest at `start_position_m` with nothing in flight.
  void begin_iteration(std::size_t iteration, double start_position_m);
  AxisSample sample();
  // Setpoint `sequence` leaves the server at `send_time_s`; false if the downlink drops it.
  bool submit_setpoint(double send_time_s, std::uint64_t sequence, double command);
  // Integrate to `end_time_s`, applying the setpoints that arrive on the way, and read the drive
  // there; the result is valid until the next call (one buffer, no allocation per cycle).
  const std::vector<AppliedSetpoint>& advance_to(double end_time_s);
  // A drive on its own time: the setpoints that have arrived by `now_s` are written now.
  const std::vector<AppliedSetpoint>& apply_arrived(double now_s);
  // When the next setpoint in flight on the emulated downlink arrives (a drive on its own time
  // is written then).
  std::optional<double> next_arrival_s() const { return downlink_.next_arrival_s(); }

  // Watchdog: no setpoint in time, so the drive is told to quick stop.
  void hold() { axis_.quick_stop(); }
  // The operator's limits tripped (or the drive failed); a node reports it and stops.
  const std::optional<std::string>& fault() const { return axis_.fault(); }
  drive::SupervisedAxis& supervised() { return axis_; }

  std::uint64_t lost_setpoints() const { return lost_; }
  std::uint64_t stale_setpoints() const { return axis_.stale_setpoints(); }

 private:
  const std::vector<AppliedSetpoint>& record(const std::vector<netsim::DelayedChannel<double>::Delivery>& deliveries);

  drive::SupervisedAxis axis_;
  plant::PositionSensor sensor_;
  netsim::DelayedChannel<double> downlink_;
  std::vector<netsim::DelayedChannel<double>::Delivery> deliveries_;
  std::vector<AppliedSetpoint> applied_;
  std::uint64_t seed_;
  std::size_t index_;
  std::uint64_t lost_ = 0;
};

}  // namespace netmc::sim
