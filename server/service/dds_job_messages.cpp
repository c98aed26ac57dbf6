#include "server/service/dds_job_messages.hpp"

#include "netsim/delay_model.hpp"

namespace netmc::service {
namespace {

void inline_trace(netmc::v1::LinkProfile& link) {
  auto& delay = *link.mutable_delay();
  if (delay.has_trace() && !delay.trace().path().empty() && delay.trace().delays_s_size() == 0) {
    for (double value : netsim::load_delay_trace_csv(delay.trace().path())) {
      delay.mutable_trace()->add_delays_s(value);
    }
    delay.mutable_trace()->clear_path();
  }
}

}  // namespace

netmc::v1::JobSpec spec_for_axes(const netmc::v1::JobSpec& spec) {
  netmc::v1::JobSpec out = spec;
  inline_trace(*out.mutable_uplink());
  inline_trace(*out.mutable_downlink());
  return out;
}

std::string axis_name(std::size_t axis) {
  return axis == 0 ? "x" : axis == 1 ? "y" : std::to_string(axis);
}

SetpointPublisher::SetpointPublisher(eprosima::fastdds::dds::DataWriter* writer,
                                     const netmc::v1::JobSpec& spec, std::uint64_t job_id)
    : writer_(writer), job_id_(job_id) {
  const std::string bytes = spec_for_axes(spec).SerializeAsString();
  spec_bytes_.assign(bytes.begin(), bytes.end());
}

void SetpointPublisher::publish(std::uint32_t axis, std::uint32_t iteration, std::uint64_t cycle,
                                netmc::dds::SetpointKind kind, double command,
                                double send_time_s, double start_position_m, bool with_spec,
                                double start_monotonic_s) {
  netmc::dds::Setpoint setpoint;
  setpoint.axis_id(axis);
  setpoint.job_id(job_id_);
  setpoint.iteration(iteration);
  setpoint.cycle(cycle);
  setpoint.kind(kind);
  setpoint.command(command);
  setpoint.send_time_s(send_time_s);
  setpoint.start_position_m(start_position_m);
  setpoint.start_monotonic_s(start_monotonic_s);
  if (with_spec) setpoint.job_spec(spec_bytes_);
  writer_->write(&setpoint);
}

void SetpointPublisher::end_job(std::uint32_t axes) {
  for (std::uint32_t axis = 0; axis < axes; ++axis) {
    publish(axis, 0, 0, netmc::dds::SETPOINT_END_JOB, 0.0, 0.0, 0.0, false, 0.0);
  }
}

void publish_iteration_log(eprosima::fastdds::dds::DataWriter* writer, std::uint64_t job_id,
                           const sim::ContourJob& job, const sim::IterationRecord& record) {
  if (!writer) return;
  const auto& m = record.metrics;
  netmc::dds::IterationLog log;
  log.job_id(job_id);
  log.iteration(static_cast<std::uint32_t>(m.iteration));
  log.total_iterations(static_cast<std::uint32_t>(job.iterations));
  log.controller(job.controller_name);
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
  log.deadline_misses(static_cast<std::uint32_t>(m.deadline_misses));
  log.lost_feedback(static_cast<std::uint32_t>(m.lost_feedback));
  log.lost_setpoints(static_cast<std::uint32_t>(m.lost_setpoints));
  log.diverged(m.diverged);
  writer->write(&log);
}

}  // namespace netmc::service
