#pragma once
// netmc-axis in realtime mode: every axis samples once a period on the node's own clock and
// applies each setpoint when it arrives (real DDS latency plus the downlink netsim delay),
// through the same AxisEndpoint as the simulation. Times are job times on the node's own clock
// (its --time-base): the server sends each iteration's start already converted to this clock
// with the offset it measured, so no clock is shared between hosts.
//
// An axis goes through phases. PREPARE_ITERATION: a simulated drive is ready at once (it restarts
// at the start position); a hardware drive is enabled through CiA 402 and moved to the start in
// CSP, and the axis says AXIS_READY when it stands there. BEGIN_ITERATION: from t = 0 the drive
// takes the job's commands (CST), sampled every period. END_ITERATION: sampling stops; a hardware
// drive returns to the start at once. END_JOB: a hardware drive stops and is switched off. A
// running axis without setpoints for the watchdog's time quick-stops.
//
// One thread does it all: it sleeps on a DDS WaitSet until the next thing is due, so a setpoint
// goes from Fast DDS's receive thread to the actuator in one wake-up, and the samples of all the
// node's axes are taken back to back.
// See docs/architecture.md, "One cycle through the code" and "Threads and queues".

#include <atomic>
#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <vector>

#include "dds_types.h"
#include "server/axis/axis_node_link.hpp"
#include "server/axis/commissioning_axis.hpp"
#include "server/axis/pending_job_starts.hpp"
#include "server/drive/point_to_point_move.hpp"
#include "server/sim/delay_statistics.hpp"

namespace netmc::axis {

class RealtimeAxisNode {
 public:
  RealtimeAxisNode(dds::DdsContext& context, AxisNodeConfig config,
                   std::chrono::milliseconds watchdog);
  AxisNodeLink& link() { return link_; }
  void serve(const std::atomic<bool>& stop);

 private:
  using Clock = std::chrono::steady_clock;

  enum class Phase {
    idle,        // no job, or its drive switched off
    preparing,   // hardware: being enabled and moved to the start
    ready,       // at the start, enabled, waiting for t = 0
    running,     // sampling (between BEGIN and END_ITERATION)
    stopping,    // hardware, END_JOB: coming to rest before it is switched off
  };

  struct OwnedAxis : JobAxis {
    Phase phase = Phase::idle;
    std::shared_ptr<drive::Drive> drive;  // hardware: for the node's life; simulated: the last job's
    std::string server;
    std::uint32_t iteration = 0;
    double start_time_s = 0.0;       // t = 0 of the iteration on this node's clock
    double start_position_m = 0.0;   // where every iteration of the job starts
    std::uint64_t next_cycle = 0;
    Clock::time_point next_sample;   // when cycle next_cycle is due (running)
    // END_ITERATION came: the report goes out at report_at, after late setpoints had time to come.
    Clock::time_point report_at;
    bool report_due = false;
    std::uint64_t commands_sent = 0; // by the server, from END_ITERATION
    double last_setpoint_s = 0.0;    // job time of the last setpoint received
    bool holding = false;            // the watchdog quick-stopped it
    std::uint64_t samples = 0;
    std::uint64_t commands_received = 0;
    // Hardware positioning: the move to the start, when it began, and which PREPARE waits.
    std::optional<drive::PointToPointMove> move;
    double move_start_s = 0.0;
    int settled_reads = 0;
    std::uint32_t ready_for = 0;      // the iteration a PREPARE asked for; 0 none
    Clock::time_point positioning_deadline;
    Clock::time_point next_poll;      // hardware outside samples: the next exchange
    Clock::time_point last_contact;   // the holder's last message (ready, preparing)
    bool poll_failed = false;         // the last idle read failed (logged once)
    Clock::time_point reset_until;    // the operator's reset of the drive is tried until then
    // Server departure time of each setpoint in flight: tau_ca then includes the real DDS
    // latency, not only the emulated part that starts when the sample reaches this node.
    std::map<std::uint64_t, double> server_send_times;
    // Round trip of the loop on this node's clock: feedback k written -> setpoint k in. The
    // newest kFeedbackTimes cycles' send times, by cycle modulo their number; a setpoint older
    // than that, or than the newest one timed, is not timed. Sized once for the node's life.
    struct FeedbackTime {
      std::uint64_t cycle = 0;
      Clock::time_point sent;
    };
    std::vector<FeedbackTime> feedback_sent;
    std::int64_t newest_timed = -1;
    // Reserved when an iteration starts (nothing allocated in a cycle), bounded however long.
    sim::DelayStatistics round_trips_s;
    sim::DelayStatistics wake_late_s;  // how late each sample was taken after its due time
    // Hardware: setpoints written as they arrived, reported with the next sample.
    std::vector<sim::AppliedSetpoint> applied_since_sample;
    drive::PowerState reported_state = drive::PowerState::not_ready_to_switch_on;
    // Hardware without a job: the operator's enable, moves, jogs and stops (netmc enable, ...).
    std::optional<CommissioningAxis> commissioning;
    std::uint64_t command_number = 0;  // the last commissioning command taken or refused
    std::string command_refusal;       // why it was refused ("" taken)
  };

  void handle(const netmc::dds::JobControl& control);
  void handle(const netmc::dds::Setpoint& setpoint);
  // The job from the message that carries its spec; false if it cannot run (refused, said) or
  // its server does not read the axis yet (pending: handled again once it does).
  bool start_job(OwnedAxis& axis, const netmc::dds::JobControl& control);
  void refuse_start(OwnedAxis& axis, const netmc::dds::JobControl& control, const std::string& why);
  // The pending starts whose server reads now (started) or whose time is over (refused).
  void settle_starts();
  void prepare(const std::string& axis_name, OwnedAxis& axis, const netmc::dds::JobControl& control);
  void begin(OwnedAxis& axis, const netmc::dds::JobControl& control);
  void end_job(const std::string& axis_name, OwnedAxis& axis, const netmc::dds::JobControl& control);
  void reset_faults(const std::vector<std::string>& axes);
  // An operator's commissioning command (CONTROL_ENABLE ... CONTROL_JOG): taken, or refused with
  // the reason in the node's status.
  void commission(const std::string& axis_name, OwnedAxis& axis, const netmc::dds::JobControl& control);
  void quick_stop_job(const std::string& axis_name, OwnedAxis& axis, const std::string& why);
  // An event of the axis's job to its server (detail at most 255 characters).
  void publish_job_event(const std::string& axis_name, const OwnedAxis& axis, std::uint32_t iteration,
                         netmc::dds::AxisEventKind kind, const std::string& detail);
  // The axis's motion and following error for the node's status.
  void report_motion(const std::string& axis_name, const OwnedAxis& axis);
  // The drive's fault reset (bit 7's edge) while one is pending (reset_until).
  void reset_drive(const std::string& axis_name, OwnedAxis& axis);
  void sample(const std::string& axis_name, OwnedAxis& axis, Clock::time_point now);
  void end_iteration(const std::string& axis_name, OwnedAxis& axis);
  void schedule(OwnedAxis& axis) const;
  // Hardware outside samples: enabling, moving, holding, stopping, or a look at an idle drive.
  void poll(const std::string& axis_name, OwnedAxis& axis, Clock::time_point now);
  void start_move(OwnedAxis& axis, double target_m, double position_m, double velocity_m_s);
  void say_ready(const std::string& axis_name, OwnedAxis& axis);
  void fail_preparation(const std::string& axis_name, OwnedAxis& axis, const std::string& why);
  void report_fault(const std::string& axis_name, OwnedAxis& axis);
  void report_drive(const std::string& axis_name, OwnedAxis& axis);
  // Samples are due until the iteration's last; setpoints are taken until END_ITERATION.
  static bool sampling(const OwnedAxis& axis) {
    return axis.phase == Phase::running && axis.endpoint && axis.next_cycle < axis.cycles;
  }
  bool hardware(const OwnedAxis& axis) const { return axis.drive && !axis.drive->virtual_time(); }
  // Hardware is exchanged with outside the samples too: between jobs, while it is positioned, and
  // from BEGIN_ITERATION to its first sample (a drive's fieldbus watchdog wants steady traffic).
  bool polled(const OwnedAxis& axis) const {
    return hardware(axis) && (axis.phase != Phase::running || axis.next_cycle == 0);
  }
  Clock::time_point wake_time(Clock::time_point next_status) const;
  void publish_status();

  AxisNodeLink link_;
  std::chrono::milliseconds watchdog_;
  std::map<std::string, OwnedAxis> axes_;
  PendingJobStarts starts_;
};

}  // namespace netmc::axis
