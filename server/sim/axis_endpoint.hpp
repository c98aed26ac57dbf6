#pragma once
// The axis-node side of one axis, as netmc-axis runs it and netmc sim calls it: the drive under
// its supervision (limits, trips, the CiA 402 master: drive::SupervisedAxis), the position sensor
// the job models on top of the drive's actual position, and the downlink on which netsim delays
// or drops each setpoint before the axis applies it. In-process runs call it directly with
// netmc's simulated drive; the distributed runs call the same code inside netmc-axis.

#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <utility>
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
  double arrival_time_s = 0.0;  // when it began to act
  // When it reached the axis, where a setpoint planned for a later instant was held until then
  // (delay compensation); the same as arrival_time_s otherwise.
  double network_arrival_s = 0.0;
  // Packetized predictive control: which of the setpoint's commands acted (0: its own; j: the
  // one meant for j periods after it, its own successor lost or late).
  std::uint32_t horizon_index = 0;
};

class AxisEndpoint {
 public:
  // Axis `axis` (its place in the group) of `job` on `drive`, under its operator's `limits`
  // (none in-process).
  AxisEndpoint(std::shared_ptr<drive::Drive> drive, const ContourJob& job, std::size_t axis,
               drive::AxisLimits limits = {});
  // netmc's simulated drive of the job's plant for axis `axis`.
  static std::shared_ptr<drive::Drive> simulated_drive(const ContourJob& job, std::size_t axis);

  // The axis node's supervision against the job (netmc-axis; in-process runs leave it out, so
  // their results stay those of the papers' loops): each sample is checked against the job's
  // reference for this axis at its instant (following error, frozen or jumping feedback), and
  // a drive on its own time must fit each cycle's exchange in the job's period.
  void follow_job_reference(const ContourJob& job);
  // Every iteration starts from rest at `start_position_m` with nothing in flight.
  void begin_iteration(std::size_t iteration, double start_position_m);
  AxisSample sample();
  // Setpoint `sequence` leaves the server at `send_time_s`; false if the downlink drops it. One
  // planned to act at `acts_at_s` (delay compensation) that arrives earlier is held until then
  // (a playout buffer: the time-varying delay becomes the constant one the server planned for);
  // a later one acts on arrival, as every setpoint without a plan does.
  bool submit_setpoint(double send_time_s, std::uint64_t sequence, double command,
                       double acts_at_s = -std::numeric_limits<double>::infinity());
  // Packetized predictive control: setpoint `sequence` carries `commands`, the first meant to act
  // at `acts_at_s`, each next one a period later. The axis plays, at each of those instants, the
  // command meant for it from the freshest setpoint it holds; a setpoint that arrives after its
  // first instant starts at its next one; with none left, the last command is held. A command
  // that is not finite trips the axis on arrival, one beyond its limit when it would act
  // (SupervisedAxis::accept_horizon, accept_horizon_entry).
  // False if the downlink drops it.
  bool submit_packet(double send_time_s, std::uint64_t sequence, double acts_at_s, std::vector<double> commands);
  // Integrate to `end_time_s`, applying the setpoints that arrive on the way, and read the drive
  // there; the result is valid until the next call (one buffer, no allocation per cycle).
  const std::vector<AppliedSetpoint>& advance_to(double end_time_s);
  // A drive on its own time: the setpoints that have arrived by `now_s` are written now.
  const std::vector<AppliedSetpoint>& apply_arrived(double now_s);
  // When the next setpoint in flight on the emulated downlink arrives (a drive on its own time
  // is written then).
  // A setpoint held for its planned instant counts as arriving then.
  // With packets: the next instant a command plays or the horizon runs out.
  std::optional<double> next_arrival_s() const;

  // Watchdog: no setpoint in time, so the drive is told to quick stop.
  void hold() { axis_.quick_stop(); }
  // The operator's limits tripped (or the drive failed); a node reports it and stops.
  const std::optional<std::string>& fault() const { return axis_.fault(); }
  drive::SupervisedAxis& supervised() { return axis_; }

  std::uint64_t lost_setpoints() const { return lost_; }
  std::uint64_t stale_setpoints() const { return axis_.stale_setpoints() + stale_packets_; }
  std::uint64_t horizon_cycles() const { return horizon_cycles_; }
  std::uint64_t held_cycles() const { return held_cycles_; }

  // Plans kept for setpoints in flight (one each; the oldest is forgotten beyond it).
  static constexpr std::size_t kMaxPlanned = 4096;
  // The longest a setpoint is held for its planned instant.
  static constexpr double kMaxHoldS = 1.0;

 private:
  using Delivery = netsim::DelayedChannel<double>::Delivery;
  const std::vector<AppliedSetpoint>& record(const std::vector<Delivery>& deliveries);
  // The deliveries due by `until_s` into deliveries_, through the playout of either kind.
  void receive(double until_s);
  // Holds the deliveries planned for later than their arrival and releases, into `deliveries`,
  // those due by `until_s` at their planned instant, sorted as the channel sorts.
  void play_out(std::vector<Delivery>& deliveries, double until_s);

  struct Planned {
    std::uint64_t sequence;
    double acts_at_s;
  };
  struct Held {
    Delivery delivery;           // arrival_time_s: when it acts
    double network_arrival_s;
  };
  std::vector<Planned> planned_;  // setpoints in flight with a plan, in sequence order
  std::vector<Held> held_;        // arrived, waiting for their instant
  // Of each of deliveries_, for record(): the setpoint it came in (a packet's sequence, not the
  // drive's), when that reached the axis, and which of its commands it is.
  struct Origin {
    std::uint64_t sequence;
    double network_arrival_s;
    std::uint32_t horizon_index;
  };
  std::vector<Origin> origins_;

  // Packetized predictive control (submit_packet).
  struct Packet {
    std::uint64_t sequence = 0;
    double send_time_s = 0.0;
    double acts_at_s = 0.0;
    double network_arrival_s = 0.0;
    std::vector<double> commands;
  };
  // Turns the packets delivered by `until_s` into the drive's deliveries, one per instant played.
  void play_packets(std::vector<Delivery>& deliveries, double until_s);
  // The first of `packet`'s instants at or after its arrival, and its index there.
  std::pair<double, double> first_instant(const Packet& packet) const;
  std::vector<Packet> packets_in_flight_;  // submitted, not yet arrived (at most kMaxPlanned)
  std::vector<Packet> packets_waiting_;    // arrived, not yet playing
  std::optional<Packet> playing_;          // the freshest that has begun to play
  std::size_t next_index_ = 0;             // of playing_'s commands, at its next instant
  std::uint64_t plays_ = 0;                // the drive's sequence: one per command played
  std::uint64_t stale_packets_ = 0, horizon_cycles_ = 0, held_cycles_ = 0;
  enum class Instant { own, horizon, held };  // what the last instant played
  Instant last_instant_ = Instant::own;
  double last_instant_s_ = -std::numeric_limits<double>::infinity();

  drive::SupervisedAxis axis_;
  plant::PositionSensor sensor_;
  netsim::DelayedChannel<double> downlink_;
  std::vector<netsim::DelayedChannel<double>::Delivery> deliveries_;
  std::vector<AppliedSetpoint> applied_;
  std::uint64_t seed_;
  std::size_t index_;
  double sample_period_s_;
  std::uint64_t lost_ = 0;
};

}  // namespace netmc::sim
