#pragma once
// What both kinds of axis node (lockstep, realtime) share: the node's identity and its claim on
// its axes, its DDS endpoints, the server that holds it, the clock probes it answers, and the
// start of a job from its spec.
// See docs/architecture.md, "Threads and queues" and "Where safety lives".

#include <atomic>
#include <chrono>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "dds_types.h"
#include "server/dds/dds_context.hpp"
#include "server/dds/time_base.hpp"
#include "server/axis/axis_drives.hpp"
#include "server/axis/sample_intake.hpp"
#include "server/drive/cia402.hpp"
#include "server/sim/axis_endpoint.hpp"

namespace netmc::axis {

// How a node brings a hardware drive to an iteration's start (a simulation is restarted there).
struct PositioningSettings {
  double velocity_m_s = 0.05;
  double acceleration_m_s2 = 0.5;
  double tolerance_m = 1e-6;        // at rest within this of the start
  double settle_velocity_m_s = 1e-4;
  std::chrono::milliseconds timeout{20000};  // beyond the move's own duration
};

struct AxisNodeConfig {
  std::string node;                    // unique node name
  std::vector<std::string> axes;       // axis names this node hosts (unique on the domain)
  std::string plant = "seed001";       // the plant model its jobs name (its simulated drives run it)
  std::string clock = "lockstep";
  dds::TimeBase time_base = dds::TimeBase::monotonic;
  // How long a holding server may stay silent before another may take the axes.
  std::chrono::milliseconds hold_lease{10000};
  std::map<std::string, AxisDrive> drives;  // by axis: the drive and the limits it runs under
  DriveSettings drive_settings;
  PositioningSettings positioning;
  // The only server this node obeys (its DDS participant name, --dds-name; under DDS Security also
  // its certificate's CN). By default netmc-server's own default name, so that no other
  // participant's job (a second site's server, a test tool, a rogue) reaches an axis unless the
  // operator says so. Empty (--any-server): any server.
  std::string server_name = "netmc-server";
};

// An axis's drive as the node last saw it, for its status.
struct AxisDriveReport {
  drive::PowerState state = drive::PowerState::not_ready_to_switch_on;
  std::uint16_t statusword = 0;
  std::uint16_t error_code = 0;
  double position_m = 0.0;
  double velocity_m_s = 0.0;
  std::string unreachable;  // why the last exchange with the drive failed ("" it answered)
};

// What an axis does for the operator's view: its motion and the last commissioning command.
struct AxisMotionReport {
  std::string motion = "off";        // off | enabling | holding | moving | jogging | stopping | job
  double following_error_m = 0.0;
  std::uint64_t command_number = 0;  // the last commissioning command taken (JobControl.job_id)
  bool command_refused = false;
  std::string command_note;          // why it was refused, or how the motion ended otherwise
};

// The node's name or one of its axes belongs to a live node already.
class NodeRefused : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// How often a node reports its status; the server forgets a node silent for kNodeExpiry.
inline constexpr std::chrono::milliseconds kStatusPeriod{500};
inline constexpr std::chrono::milliseconds kNodeExpiry{2500};

// One axis of a job as a node runs it.
struct JobAxis {
  std::unique_ptr<sim::AxisEndpoint> endpoint;
  std::uint64_t job_id = 0;
  std::size_t cycles = 0;
  double sample_period_s = 0.0;
  bool fault_reported = false;
};

class AxisNodeLink {
 public:
  AxisNodeLink(dds::DdsContext& context, AxisNodeConfig config);
  ~AxisNodeLink();
  AxisNodeLink(const AxisNodeLink&) = delete;
  AxisNodeLink& operator=(const AxisNodeLink&) = delete;

  // Listens to the other nodes' status for a while; throws NodeRefused (after saying so on the
  // status topic) if the name or an axis is taken by a live node.
  void claim(std::chrono::milliseconds listen);

  const AxisNodeConfig& config() const { return config_; }
  bool hosts(const std::string& axis) const;
  // Triggered while job controls wait for take_control: for the loop's WaitSet.
  eprosima::fastdds::dds::GuardCondition& control_arrived() { return control_intake_.arrived(); }
  // Triggered while setpoints wait for take_setpoint: for the loop's WaitSet.
  eprosima::fastdds::dds::GuardCondition& setpoint_arrived() { return setpoint_intake_.arrived(); }
  // The next job control for an axis of this node that was sent by the participant its `server`
  // field names, from a server this node obeys. The others are dropped on Fast DDS's receive
  // thread as they arrive (SampleIntake), so that a flood of them cannot push a server's own out:
  // forgeries (a participant speaking as a server it is not) are counted, and each forging
  // participant logged once, so that no foreign sample holds, moves or makes stale an axis of a
  // server's job.
  std::optional<netmc::dds::JobControl> take_control();
  // The next setpoint of the server that holds its axis, for the job it holds it for. The others
  // (forged, of another job or of no job here) are dropped on Fast DDS's receive thread as they
  // arrive (SampleIntake): they neither displace the job's own nor wait for the node's loop.
  std::optional<netmc::dds::Setpoint> take_setpoint() { return setpoint_intake_.take(); }
  void publish(netmc::dds::Feedback& feedback);
  void publish_event(netmc::dds::AxisEvent& event);
  void publish_status(netmc::dds::NodeHealth health, const std::string& detail);
  // Tells the server of `control` (and this node's log) why its job is not taken.
  void refuse(const netmc::dds::JobControl& control, netmc::dds::AxisEventKind kind, const std::string& why);

  // The server that holds an axis (each axis on its own: the axes of one node may run different
  // jobs, of different servers, at once). A BEGIN of a new job is taken only from the holder or
  // when no live server holds the axis; every other message only from the holder of that job.
  // Returns an empty string if `control` may proceed, else why not.
  std::string admit(const netmc::dds::JobControl& control);
  bool from_holder(const std::string& axis, const std::string& server, std::uint64_t job_id);
  void release(const std::string& axis, const std::string& server, std::uint64_t job_id);

  // Whether the node and the server of `begin` are matched both ways: the server reads the axis's
  // feedback and events, and this node's setpoint reader hears that server's setpoint writer (by
  // identity: a dead server's reader, still counted by DDS, does not do). A node that began before
  // it heard the writer would drop the job's first setpoints (a best-effort reader takes nothing
  // from a writer it has not matched: one lost discovery datagram delays that by seconds) and its
  // watchdog would stop the axis. Looked at, never waited for: the node's loop keeps the start
  // pending (PendingJobStarts) until it holds.
  bool linked_to_server(const netmc::dds::JobControl& begin) const;
  // From the message that carries the job's spec (BEGIN_ITERATION of iteration 1 in lockstep,
  // PREPARE_ITERATION in realtime), once linked to its server: the job's axis, built from its
  // spec, on the axis's drive. Throws for an axis in fault (named with its reason), a server not
  // linked, or a spec this node cannot run.
  JobAxis start_job(const netmc::dds::JobControl& begin);
  // Why the start of `begin` is not linked (for one given up after PendingJobStarts::kLinkTimeout).
  std::string why_not_linked(const netmc::dds::JobControl& begin) const;

  // Faults latch per axis until the operator resets them: `netmc reset` through a server this
  // node obeys, SIGUSR1 to netmc-axis, or a restart. report_fault latches the endpoint's fault
  // (once per job axis), tells the job's server (AXIS_FAULT) and the node's log; the status shows
  // it. reset_faults clears the latched faults of `axes` (all if empty) and returns them.
  void report_fault(const std::string& axis, JobAxis& job_axis, const std::string& server, std::uint32_t iteration);
  std::vector<std::string> reset_faults(const std::vector<std::string>& axes = {});
  bool faulted() const;
  bool faulted(const std::string& axis) const;
  // Why the axis cannot start a job now, beside a latched fault: its drive does not answer or is
  // in Fault ("" none).
  std::string drive_problem(const std::string& axis) const;
  // Called by the node's loop: the axes whose faults the operator reset by signal
  // (fault_reset_requested), all of them, or none.
  std::vector<std::string> poll_fault_reset();
  // What the node's loop last saw of an axis's drive: the status carries it.
  void report_drive(const std::string& axis, drive::PowerState state, const drive::DriveFeedback& feedback);
  // The drive did not answer (`cause`): the node is in fault, naming it, until it answers again.
  void report_unreachable(const std::string& axis, const std::string& cause);
  void report_motion(const std::string& axis, const std::string& motion, double following_error_m);
  void report_command(const std::string& axis, std::uint64_t number, bool refused, const std::string& note);
  // Whether `control` asks for a fault reset that this node takes (from a server it obeys).
  bool reset_request(const netmc::dds::JobControl& control) const;
  // Whether `control` is an operator's commissioning command (enable, disable, quick stop, move,
  // jog) for an axis of this node (from a server it obeys).
  bool commissioning_request(const netmc::dds::JobControl& control) const;

  // The node's own clock (its --time-base).
  double now_s() const { return dds::time_base_now_s(config_.time_base); }

 private:
  void answer_probes();
  // True if `server` is the sender's identity; else counts and logs the forgery.
  bool authentic(const eprosima::fastrtps::rtps::GuidPrefix_t& sender, const std::string& server, const char* what,
                 const std::string& axis);

  struct Hold {
    std::string server;
    std::uint64_t job_id = 0;
    std::chrono::steady_clock::time_point last_contact{};
  };
  // Writers of one axis: feedback and events travel in the axis's partition, so that a job's
  // readers on the server see its own axes only.
  struct AxisWriters {
    eprosima::fastdds::dds::DataWriter* feedback = nullptr;
    eprosima::fastdds::dds::DataWriter* events = nullptr;
  };
  // linked_to_server's first half: the server of `begin` reads the axis's feedback and events.
  bool server_reads(const netmc::dds::JobControl& begin) const;
  bool held(const Hold& hold, std::chrono::steady_clock::time_point now) const;
  // The setpoint intake's filter: authentic, and of the holder of its axis for the job it holds.
  bool from_holder_of_job(const eprosima::fastrtps::rtps::GuidPrefix_t& sender, const netmc::dds::Setpoint& setpoint);
  const AxisWriters& writers_of(const std::string& axis) const;

  dds::DdsContext& context_;
  AxisNodeConfig config_;
  std::map<std::string, AxisWriters> writers_;
  eprosima::fastdds::dds::DataWriter* status_writer_;
  eprosima::fastdds::dds::DataWriter* reply_writer_;
  dds::SampleReader<netmc::dds::ClockProbe> probes_;
  SampleIntake<netmc::dds::JobControl> control_intake_;
  SampleIntake<netmc::dds::Setpoint> setpoint_intake_;
  // Made in the constructor's body, once everything their filters read exists.
  eprosima::fastdds::dds::DataReader* control_reader_ = nullptr;
  eprosima::fastdds::dds::DataReader* setpoint_reader_ = nullptr;

  // True if --server-name lets the participant `sender` command this node; logs a refusal once
  // per participant.
  bool obeys(const eprosima::fastrtps::rtps::GuidPrefix_t& sender);

  mutable std::mutex mutex_;  // status, holds and faults: the probe thread and the node's thread
  std::map<std::string, Hold> holds_;  // by axis
  std::map<std::string, std::string> faults_;  // by axis: the reason
  std::map<std::string, std::string> last_faults_;  // by axis: the latest reason, kept after a reset
  std::map<std::string, AxisDriveReport> drive_reports_;  // by axis
  std::map<std::string, AxisMotionReport> motion_reports_;  // by axis
  std::map<std::string, bool> obeyed_;  // --server-name's verdict by participant (bounded)

  std::atomic<std::uint64_t> forged_{0};
  std::set<std::string> forgers_logged_;  // "participant kind", bounded: kMaxForgersLogged
  bool refused_ = false;
  std::atomic<bool> stop_{false};
  std::thread probe_thread_;
};

// Set by netmc-axis's SIGUSR1 handler (async-signal-safe), taken by poll_fault_reset.
std::atomic<bool>& fault_reset_requested();

// Copies setpoints applied by the actuator into a feedback sample.
void append_applied(netmc::dds::Feedback& feedback, const std::vector<sim::AppliedSetpoint>& applied);
// One applied setpoint as the data plane carries it.
netmc::dds::AppliedSetpoint applied_entry(const sim::AppliedSetpoint& applied);
// The instant a setpoint is meant to act (Setpoint.acts_at_s, delay compensation), for
// AxisEndpoint::submit_setpoint; -inf (on arrival) for 0 or a value that is not finite.
double planned_instant(const netmc::dds::Setpoint& setpoint);
// Hands a setpoint that left for the actuator at `send_time_s` (job time) to `endpoint`: with a
// horizon (packets) its horizon's commands, else its one.
void submit_to(sim::AxisEndpoint& endpoint, double send_time_s, const netmc::dds::Setpoint& setpoint);
// The endpoint's downlink counters of the iteration into a feedback or an axis event.
template <typename Message>
void set_downlink_counters(Message& message, const sim::AxisEndpoint& endpoint) {
  message.lost_setpoints(endpoint.lost_setpoints());
  message.stale_setpoints(endpoint.stale_setpoints());
  message.horizon_cycles(endpoint.horizon_cycles());
  message.held_cycles(endpoint.held_cycles());
}
// Fills the sample fields of a feedback.
void set_sample(netmc::dds::Feedback& feedback, std::uint64_t cycle, double time_s,
                const sim::AxisSample& sample);
// Parses --axes: comma-separated axis names.
std::vector<std::string> parse_axis_list(const std::string& text);

}  // namespace netmc::axis
