#pragma once
// What netmc-server's job runners (lockstep and realtime) say over DDS: job control, the
// commands of each cycle, the iteration log, and what the axes report back about a job.

#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "dds_types.h"
#include "idl/job.pb.h"
#include "server/dds/dds_context.hpp"
#include "server/sim/contour_job.hpp"
#include "server/sim/contour_server.hpp"
#include "server/sim/iteration_metrics.hpp"

namespace netmc::service {

// An axis node stopped answering, refused the job or reported a fault: the job cannot go on.
class JobFailure : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct JobChannels {
  std::string server;                                       // this server's identity
  std::vector<std::string> axes;                            // axis names, in the job's order
  eprosima::fastdds::dds::DataWriter* control = nullptr;    // JobControl
  std::vector<eprosima::fastdds::dds::DataWriter*> setpoints;  // per axis: Setpoint, the job's clock
  dds::SampleReader<netmc::dds::Feedback>* feedback = nullptr;
  dds::SampleReader<netmc::dds::AxisEvent>* events = nullptr;
  eprosima::fastdds::dds::DataWriter* iteration_logs = nullptr;
  // The participant (GUID prefix) of the node hosting each axis, in the job's order: feedback
  // and events about an axis are believed only from it.
  std::vector<std::string> nodes;
  // Samples about the job's axes that came from another participant: dropped, counted here.
  mutable std::uint64_t forged_samples = 0;
};

// True if the node hosting the job's axis `axis` sent the sample `sender` sent; else counts a
// forgery (a participant speaking for an axis it does not host, e.g. to steer the controller
// with fake feedback or end the job with a fake fault).
bool from_axis_node(const JobChannels& channels, std::size_t axis,
                    const eprosima::fastrtps::rtps::GuidPrefix_t& sender);

class JobPublisher {
 public:
  JobPublisher(const JobChannels& channels, const netmc::v1::JobSpec& spec, std::uint64_t job_id);
  // Lockstep: the job's spec travels with iteration 1's BEGIN. Realtime: with iteration 1's
  // PREPARE, and every iteration begins once its axes said AXIS_READY.
  void prepare_iteration(std::size_t axis, std::uint32_t iteration, double start_position_m);
  void begin_iteration(std::size_t axis, std::uint32_t iteration, double start_position_m,
                       double start_time_s, bool with_spec);
  void end_iteration(std::size_t axis, std::uint32_t iteration, std::uint64_t cycle);
  // The axis's part of a cycle's command, and with packets its horizon. `acts_at_s`: when the
  // command is meant to act (delay compensation); not finite: on arrival.
  void command(std::size_t axis, std::uint32_t iteration, std::uint64_t cycle, const sim::CycleCommand& command,
               double send_time_s, double acts_at_s);
  // Releases every axis (never throws: it runs on the way out of failed jobs too).
  void end_job() noexcept;
  // Every axis's drive quick-stops now (a limit the job crossed); the job ends after.
  void quick_stop(std::uint32_t iteration) noexcept;
  std::uint64_t job_id() const { return job_id_; }

 private:
  netmc::dds::JobControl control(std::size_t axis, std::uint32_t iteration,
                                 netmc::dds::ControlKind kind) const;

  const JobChannels& channels_;
  std::vector<std::uint8_t> spec_bytes_;
  std::uint64_t job_id_;
};

// Takes the axes' events of this server's job `job_id`: throws JobFailure on a refusal or a
// fault, hands iteration ends and readiness (AXIS_ITERATION_ENDED, AXIS_READY) to `on_event`.
void poll_axis_events(const JobChannels& channels, std::uint64_t job_id,
                      const std::function<void(const netmc::dds::AxisEvent&)>& on_event);
// Waits until `until` for the next event of this server's job `job_id` and handles it as
// poll_axis_events does; false if none came.
bool wait_axis_event(const JobChannels& channels, std::uint64_t job_id, std::chrono::steady_clock::time_point until,
                     const std::function<void(const netmc::dds::AxisEvent&)>& on_event);
// Index of `axis` in channels.axes, or channels.axes.size() if it is not the job's.
std::size_t axis_index(const JobChannels& channels, const std::string& axis);

void publish_iteration_log(const JobChannels& channels, std::uint64_t job_id,
                           const sim::ContourJob& job, const sim::IterationRecord& record);

}  // namespace netmc::service
