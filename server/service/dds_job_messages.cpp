#include "server/service/dds_job_messages.hpp"

#include <algorithm>
#include <cmath>

#include "netsim/delay_model.hpp"

namespace netmc::service {
JobPublisher::JobPublisher(const JobChannels& channels, const netmc::v1::JobSpec& spec, std::uint64_t job_id)
    : channels_(channels), job_id_(job_id) {
  const std::string bytes = spec.SerializeAsString();  // delay traces inline: the server reads no file
  if (bytes.size() > netmc::dds::kMaxJobSpec) {
    throw JobFailure("the job spec for the axes takes " + std::to_string(bytes.size()) + " bytes, more than " +
                     std::to_string(netmc::dds::kMaxJobSpec));
  }
  spec_bytes_.assign(bytes.begin(), bytes.end());
}

netmc::dds::JobControl JobPublisher::control(std::size_t axis, std::uint32_t iteration,
                                             netmc::dds::ControlKind kind) const {
  netmc::dds::JobControl c;
  c.axis(channels_.axes.at(axis));
  c.server(channels_.server);
  c.job_id(job_id_);
  c.iteration(iteration);
  c.kind(kind);
  return c;
}

void JobPublisher::prepare_iteration(std::size_t axis, std::uint32_t iteration, double start_position_m) {
  auto c = control(axis, iteration, netmc::dds::CONTROL_PREPARE_ITERATION);
  c.start_position_m(start_position_m);
  if (iteration == 1) c.job_spec(spec_bytes_);
  dds::write_checked(channels_.control, &c);
}

void JobPublisher::begin_iteration(std::size_t axis, std::uint32_t iteration, double start_position_m,
                                   double start_time_s, bool with_spec) {
  auto c = control(axis, iteration, netmc::dds::CONTROL_BEGIN_ITERATION);
  c.start_position_m(start_position_m);
  c.start_time_s(start_time_s);
  if (with_spec && iteration == 1) c.job_spec(spec_bytes_);
  dds::write_checked(channels_.control, &c);
}

void JobPublisher::end_iteration(std::size_t axis, std::uint32_t iteration, std::uint64_t cycle) {
  auto c = control(axis, iteration, netmc::dds::CONTROL_END_ITERATION);
  c.cycle(cycle);
  dds::write_checked(channels_.control, &c);
}

void JobPublisher::command(std::size_t axis, std::uint32_t iteration, std::uint64_t cycle,
                           const sim::CycleCommand& command, double send_time_s, double acts_at_s) {
  netmc::dds::Setpoint setpoint;
  setpoint.axis(channels_.axes.at(axis));
  setpoint.server(channels_.server);
  setpoint.job_id(job_id_);
  setpoint.iteration(iteration);
  setpoint.cycle(cycle);
  setpoint.command(command.command[static_cast<Eigen::Index>(axis)]);
  setpoint.send_time_s(send_time_s);
  setpoint.acts_at_s(std::isfinite(acts_at_s) ? acts_at_s : 0.0);
  if (command.horizon_length > 0) {  // packets: this axis's row of the horizon
    const auto first = command.horizon.begin() + static_cast<std::ptrdiff_t>(axis * command.horizon_length);
    setpoint.horizon().assign(first, first + static_cast<std::ptrdiff_t>(command.horizon_length));
  }
  dds::write_checked(channels_.setpoints.at(axis), &setpoint);
}

void JobPublisher::quick_stop(std::uint32_t iteration) noexcept {
  for (std::size_t axis = 0; axis < channels_.axes.size(); ++axis) {
    try {
      auto c = control(axis, iteration, netmc::dds::CONTROL_QUICK_STOP);
      dds::write_checked(channels_.control, &c);
    } catch (const std::exception&) {
      // The axis's watchdog stops it when no setpoint follows.
    }
  }
}

void JobPublisher::end_job() noexcept {
  for (std::size_t axis = 0; axis < channels_.axes.size(); ++axis) {
    try {
      auto c = control(axis, 0, netmc::dds::CONTROL_END_JOB);
      dds::write_checked(channels_.control, &c);
    } catch (const std::exception&) {
      // The axis's hold lease frees it if this is lost.
    }
  }
}

std::size_t axis_index(const JobChannels& channels, const std::string& axis) {
  return static_cast<std::size_t>(std::find(channels.axes.begin(), channels.axes.end(), axis) -
                                  channels.axes.begin());
}

bool from_axis_node(const JobChannels& channels, std::size_t axis,
                    const eprosima::fastrtps::rtps::GuidPrefix_t& sender) {
  if (axis < channels.nodes.size() && dds::sent_by(sender, channels.nodes[axis])) return true;
  ++channels.forged_samples;
  return false;
}

namespace {

// True if `event` is an iteration end or a readiness of this job (handed to `on_event`); throws on
// a refusal or fault.
bool handle_axis_event(const JobChannels& channels, std::uint64_t job_id, const netmc::dds::AxisEvent& event,
                       const std::function<void(const netmc::dds::AxisEvent&)>& on_event) {
  const std::size_t axis = axis_index(channels, event.axis());
  if (event.server() != channels.server || event.job_id() != job_id || axis >= channels.axes.size() ||
      !from_axis_node(channels, axis, channels.events->last_sender())) {
    return false;
  }
  switch (event.kind()) {
    case netmc::dds::AXIS_REFUSED:
      throw JobFailure("axis " + event.axis() + " refused the job: " + event.detail());
    case netmc::dds::AXIS_FAULT:
      throw JobFailure("axis " + event.axis() + " cannot run the job: " + event.detail());
    case netmc::dds::AXIS_ITERATION_ENDED:
    case netmc::dds::AXIS_READY:
      if (on_event) on_event(event);
      return true;
  }
  return false;
}

}  // namespace

void poll_axis_events(const JobChannels& channels, std::uint64_t job_id,
                      const std::function<void(const netmc::dds::AxisEvent&)>& on_event) {
  while (auto event = channels.events->try_take()) handle_axis_event(channels, job_id, *event, on_event);
}

bool wait_axis_event(const JobChannels& channels, std::uint64_t job_id, std::chrono::steady_clock::time_point until,
                     const std::function<void(const netmc::dds::AxisEvent&)>& on_event) {
  while (auto event = channels.events->take_until(until)) {
    if (handle_axis_event(channels, job_id, *event, on_event)) return true;
  }
  return false;
}

void publish_iteration_log(const JobChannels& channels, std::uint64_t job_id,
                           const sim::ContourJob& job, const sim::IterationRecord& record) {
  if (!channels.iteration_logs) return;
  const auto& m = record.metrics;
  netmc::dds::IterationLog log;
  log.server(channels.server);
  log.job_id(job_id);
  log.iteration(static_cast<std::uint32_t>(m.iteration));
  log.total_iterations(static_cast<std::uint32_t>(job.iterations));
  log.controller(job.controller_name.substr(0, 64));
  log.e_max_m(m.e_max_m);
  log.e_rms_m(m.e_rms_m);
  log.e_sum_m(m.e_sum_m);
  log.tau_mean_s(m.tau_mean_s);
  log.tau_p99_s(m.tau_p99_s);
  log.tau_max_s(m.tau_max_s);
  log.tau_sc_mean_s(m.tau_sc_mean_s);
  log.tau_sc_p99_s(m.tau_sc_p99_s);
  log.tau_sc_max_s(m.tau_sc_max_s);
  log.tau_cc_mean_s(m.tau_cc_mean_s);
  log.tau_cc_p99_s(m.tau_cc_p99_s);
  log.tau_cc_max_s(m.tau_cc_max_s);
  log.tau_ca_mean_s(m.tau_ca_mean_s);
  log.tau_ca_p99_s(m.tau_ca_p99_s);
  log.tau_ca_max_s(m.tau_ca_max_s);
  log.clock_uncertainty_s(m.clock_uncertainty_s);
  log.deadline_misses(static_cast<std::uint32_t>(m.deadline_misses));
  log.lost_feedback(static_cast<std::uint32_t>(m.lost_feedback));
  log.lost_setpoints(static_cast<std::uint32_t>(m.lost_setpoints));
  log.diverged(m.diverged);
  dds::write_checked(channels.iteration_logs, &log);
}

}  // namespace netmc::service
