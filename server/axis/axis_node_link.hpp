#pragma once
// What both kinds of axis node (lockstep, realtime) share: the node's identity and its claim on
// its axes, its DDS endpoints, the server that holds it, the clock probes it answers, and the
// start of a job from its spec.

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
#include "server/sim/axis_endpoint.hpp"

namespace netmc::axis {

struct AxisNodeConfig {
  std::string node;                    // unique node name
  std::vector<std::string> axes;       // axis names this node hosts (unique on the domain)
  std::string plant = "seed001";       // the plant model this node hosts
  std::string clock = "lockstep";
  dds::TimeBase time_base = dds::TimeBase::monotonic;
  // How long a holding server may stay silent before another may take the axes.
  std::chrono::milliseconds hold_lease{10000};
  std::map<std::string, drive::AxisLimits> limits;  // the operator's, by axis (an axis not here has none)
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
  dds::SampleReader<netmc::dds::JobControl>& control() { return control_; }
  dds::SampleReader<netmc::dds::Setpoint>& setpoints() { return setpoints_; }
  // The next job control or setpoint that was sent by the participant its `server` field names.
  // Others are forgeries (a participant speaking as a server it is not): dropped, counted, and
  // each forging participant logged once, so that no foreign sample holds, moves or makes stale
  // an axis of a server's job.
  std::optional<netmc::dds::JobControl> take_control();
  std::optional<netmc::dds::Setpoint> take_setpoint();
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

  // From the BEGIN_ITERATION of iteration 1: the job's axis, built from its spec. Throws for an
  // axis in fault (named with its reason) or a spec this node cannot run.
  JobAxis start_job(const netmc::dds::JobControl& begin);

  // Faults latch per axis until the operator resets them on this host (SIGUSR1 to netmc-axis,
  // or a restart): a server cannot clear them. report_fault latches the endpoint's fault (once
  // per job axis), tells the job's server (AXIS_FAULT) and the node's log; the status shows it.
  void report_fault(const std::string& axis, JobAxis& job_axis, const std::string& server, std::uint32_t iteration);
  void reset_faults();
  bool faulted() const;
  // Called by the node's loop: resets the faults if the operator asked (fault_reset_requested).
  void poll_fault_reset();

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
  bool held(const Hold& hold, std::chrono::steady_clock::time_point now) const;
  const AxisWriters& writers_of(const std::string& axis) const;

  dds::DdsContext& context_;
  AxisNodeConfig config_;
  std::map<std::string, AxisWriters> writers_;
  eprosima::fastdds::dds::DataWriter* status_writer_;
  eprosima::fastdds::dds::DataWriter* reply_writer_;
  dds::SampleReader<netmc::dds::JobControl> control_;
  dds::SampleReader<netmc::dds::Setpoint> setpoints_;
  dds::SampleReader<netmc::dds::ClockProbe> probes_;

  mutable std::mutex mutex_;  // status, holds and faults: the probe thread and the node's thread
  std::map<std::string, Hold> holds_;  // by axis
  std::map<std::string, std::string> faults_;  // by axis: the reason

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
// Fills the sample fields of a feedback.
void set_sample(netmc::dds::Feedback& feedback, std::uint64_t cycle, double time_s,
                const sim::AxisSample& sample);
// Parses --axes: comma-separated axis names.
std::vector<std::string> parse_axis_list(const std::string& text);

}  // namespace netmc::axis
