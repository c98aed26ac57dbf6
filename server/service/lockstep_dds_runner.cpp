#include "server/service/lockstep_dds_runner.hpp"

#include "netsim/delay_model.hpp"
#include "server/job/job_builder.hpp"

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

std::string axis_name(std::size_t axis) { return axis == 0 ? "x" : axis == 1 ? "y" : std::to_string(axis); }

}  // namespace

netmc::v1::JobSpec spec_for_axes(const netmc::v1::JobSpec& spec) {
  netmc::v1::JobSpec out = spec;
  inline_trace(*out.mutable_uplink());
  inline_trace(*out.mutable_downlink());
  return out;
}

LockstepDdsRunner::LockstepDdsRunner(LockstepChannels channels, const netmc::v1::JobSpec& spec,
                                     std::uint64_t job_id, std::chrono::milliseconds axis_timeout)
    : channels_(channels),
      job_(job::build_contour_job(spec)),
      server_(job_),
      job_id_(job_id),
      axis_timeout_(axis_timeout) {
  const std::string bytes = spec_for_axes(spec).SerializeAsString();
  spec_bytes_.assign(bytes.begin(), bytes.end());
}

void LockstepDdsRunner::publish(std::uint32_t axis, std::uint32_t iteration, std::uint64_t cycle,
                                netmc::dds::SetpointKind kind, double command,
                                double send_time_s, double start_position_m, bool with_spec) {
  netmc::dds::Setpoint setpoint;
  setpoint.axis_id(axis);
  setpoint.job_id(job_id_);
  setpoint.iteration(iteration);
  setpoint.cycle(cycle);
  setpoint.kind(kind);
  setpoint.command(command);
  setpoint.send_time_s(send_time_s);
  setpoint.start_position_m(start_position_m);
  if (with_spec) setpoint.job_spec(spec_bytes_);
  channels_.setpoints->write(&setpoint);
}

std::vector<netmc::dds::Feedback> LockstepDdsRunner::collect(std::uint32_t iteration,
                                                            std::uint64_t cycle) {
  const std::size_t axes = job_.axes.size();
  std::vector<netmc::dds::Feedback> out(axes);
  std::vector<bool> have(axes, false);
  std::size_t missing = axes;
  const auto deadline = std::chrono::steady_clock::now() + axis_timeout_;
  while (missing > 0) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    auto sample = left.count() > 0 ? channels_.feedback->take(left) : std::nullopt;
    if (!sample) {
      std::string names;
      for (std::size_t axis = 0; axis < axes; ++axis) {
        if (!have[axis]) names += (names.empty() ? "" : ", ") + axis_name(axis);
      }
      throw JobFailure("axis " + names + " did not answer cycle " + std::to_string(cycle) +
                       " of iteration " + std::to_string(iteration) + " within " +
                       std::to_string(axis_timeout_.count()) + " ms (node stopped or unreachable)");
    }
    // Samples of earlier jobs or cycles may still arrive; only this exchange counts.
    if (sample->job_id() != job_id_ || sample->iteration() != iteration ||
        sample->cycle() != cycle || sample->axis_id() >= axes || have[sample->axis_id()]) {
      continue;
    }
    have[sample->axis_id()] = true;
    out[sample->axis_id()] = std::move(*sample);
    --missing;
  }
  return out;
}

void LockstepDdsRunner::end_job() {
  for (std::uint32_t axis = 0; axis < job_.axes.size(); ++axis) {
    publish(axis, 0, 0, netmc::dds::SETPOINT_END_JOB, 0.0, 0.0, 0.0, false);
  }
}

void LockstepDdsRunner::run(const std::function<void(const sim::IterationRecord&)>& on_iteration,
                            const std::atomic<bool>& cancel) {
  const auto axes = static_cast<std::uint32_t>(job_.axes.size());
  const std::size_t cycles = server_.cycles();
  const double h = job_.sample_period_s;
  try {
    for (std::uint32_t iteration = 1; iteration <= job_.iterations && !cancel.load(); ++iteration) {
      const Eigen::Vector2d start = server_.begin_iteration(iteration);
      for (std::uint32_t axis = 0; axis < axes; ++axis) {
        publish(axis, iteration, 0, netmc::dds::SETPOINT_BEGIN_ITERATION, 0.0, 0.0,
                start[static_cast<Eigen::Index>(axis)], iteration == 1);
      }
      auto responses = collect(iteration, 0);
      bool cancelled = false;
      for (std::uint32_t axis = 0; axis < axes; ++axis) {
        server_.submit_feedback(axis, 0, 0.0,
                                {responses[axis].position_m(), responses[axis].true_position_m()});
      }
      for (std::size_t k = 0; k < cycles; ++k) {
        const sim::CycleCommand command = server_.compute_cycle(k);
        if (command.diverged || cancel.load()) {
          cancelled = !command.diverged;
          for (std::uint32_t axis = 0; axis < axes; ++axis) {
            publish(axis, iteration, k, netmc::dds::SETPOINT_END_ITERATION, 0.0, 0.0, 0.0, false);
          }
          responses = collect(iteration, k);
          break;
        }
        for (std::uint32_t axis = 0; axis < axes; ++axis) {
          publish(axis, iteration, k, netmc::dds::SETPOINT_COMMAND,
                  command.command[static_cast<Eigen::Index>(axis)], command.send_time_s, 0.0, false);
        }
        responses = collect(iteration, k + 1);
        if (k + 1 == cycles) break;
        // Same order as the in-process runner: every axis's applied setpoints, then every
        // axis's new sample (the delay statistics sum in this order).
        for (std::uint32_t axis = 0; axis < axes; ++axis) {
          std::vector<sim::AppliedSetpoint> applied;
          for (const auto& a : responses[axis].applied()) {
            applied.push_back({a.cycle(), a.send_time_s(), a.arrival_time_s()});
          }
          server_.record_applied(axis, applied);
        }
        const double t = static_cast<double>(k + 1) * h;
        for (std::uint32_t axis = 0; axis < axes; ++axis) {
          server_.submit_feedback(axis, k + 1, t,
                                  {responses[axis].position_m(), responses[axis].true_position_m()});
        }
      }
      std::uint64_t lost = 0, stale = 0;
      for (const auto& response : responses) {
        lost += response.lost_setpoints();
        stale += response.stale_setpoints();
      }
      const sim::IterationRecord record = server_.end_iteration(lost, stale);
      if (cancelled) break;  // a partial iteration is not reported
      netmc::dds::IterationLog log;
      log.job_id(job_id_);
      log.iteration(static_cast<std::uint32_t>(record.metrics.iteration));
      log.total_iterations(static_cast<std::uint32_t>(job_.iterations));
      log.controller(job_.controller_name);
      log.e_max_m(record.metrics.e_max_m);
      log.e_rms_m(record.metrics.e_rms_m);
      log.e_sum_m(record.metrics.e_sum_m);
      log.tau_mean_s(record.metrics.tau_mean_s);
      log.tau_p99_s(record.metrics.tau_p99_s);
      log.tau_max_s(record.metrics.tau_max_s);
      log.deadline_misses(static_cast<std::uint32_t>(record.metrics.deadline_misses));
      log.lost_feedback(static_cast<std::uint32_t>(record.metrics.lost_feedback));
      log.lost_setpoints(static_cast<std::uint32_t>(record.metrics.lost_setpoints));
      log.diverged(record.metrics.diverged);
      if (channels_.iteration_logs) channels_.iteration_logs->write(&log);
      if (on_iteration) on_iteration(record);
      if (record.metrics.diverged) break;
    }
  } catch (...) {
    end_job();
    throw;
  }
  end_job();
}

}  // namespace netmc::service
