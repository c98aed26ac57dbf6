#include "server/service/lockstep_dds_runner.hpp"

#include "server/job/job_builder.hpp"

namespace netmc::service {

LockstepDdsRunner::LockstepDdsRunner(const JobChannels& channels, const netmc::v1::JobSpec& spec,
                                     std::uint64_t job_id, std::chrono::milliseconds axis_timeout,
                                     const job::JobBuildOptions& build)
    : channels_(channels),
      job_(job::build_contour_job(spec, build)),
      server_(job_),
      publisher_(channels, spec, job_id),
      axis_timeout_(axis_timeout) {}

std::vector<netmc::dds::Feedback> LockstepDdsRunner::collect(std::uint32_t iteration,
                                                            std::uint64_t cycle) {
  const std::size_t axes = job_.axes.size();
  std::vector<netmc::dds::Feedback> out(axes);
  std::vector<bool> have(axes, false);
  std::size_t missing = axes;
  const auto deadline = std::chrono::steady_clock::now() + axis_timeout_;
  while (missing > 0) {
    // A refusal or fault ends the job at once, with the axis's reason.
    poll_axis_events(channels_, publisher_.job_id(), nullptr);
    const auto now = std::chrono::steady_clock::now();
    if (now >= deadline) {
      std::string names;
      for (std::size_t axis = 0; axis < axes; ++axis) {
        if (!have[axis]) names += (names.empty() ? "" : ", ") + channels_.axes[axis];
      }
      throw JobFailure("axis " + names + " did not answer cycle " + std::to_string(cycle) +
                       " of iteration " + std::to_string(iteration) + " within " +
                       std::to_string(axis_timeout_.count()) + " ms (node stopped or unreachable)");
    }
    auto sample = channels_.feedback->take_until(std::min(deadline, now + std::chrono::milliseconds(50)));
    if (!sample) continue;
    // Samples of other servers, earlier jobs or cycles may still arrive; only this exchange counts.
    const std::size_t axis = axis_index(channels_, sample->axis());
    if (sample->server() != channels_.server || sample->job_id() != publisher_.job_id() ||
        sample->iteration() != iteration || sample->cycle() != cycle || axis >= axes ||
        !from_axis_node(channels_, axis, channels_.feedback->last_sender()) || have[axis]) {
      continue;
    }
    have[axis] = true;
    out[axis] = std::move(*sample);
    --missing;
  }
  return out;
}

void LockstepDdsRunner::run(const std::function<void(const sim::IterationRecord&)>& on_iteration,
                            const std::atomic<bool>& cancel) {
  const auto axes = static_cast<std::uint32_t>(job_.axes.size());
  const std::size_t cycles = server_.cycles();
  const double h = job_.sample_period_s;
  try {
    for (std::uint32_t iteration = 1; iteration <= job_.iterations && !cancel.load(); ++iteration) {
      const control::AxisVector start = server_.begin_iteration(iteration);
      for (std::uint32_t axis = 0; axis < axes; ++axis) {
        publisher_.begin_iteration(axis, iteration, start[static_cast<Eigen::Index>(axis)], 0.0, true);
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
            publisher_.end_iteration(axis, iteration, k);
          }
          responses = collect(iteration, k);
          break;
        }
        for (std::uint32_t axis = 0; axis < axes; ++axis) {
          publisher_.command(axis, iteration, k, command, command.send_time_s, command.acts_at_s);
        }
        responses = collect(iteration, k + 1);
        if (k + 1 == cycles) break;
        // Same order as the in-process runner: every axis's applied setpoints, then every
        // axis's new sample (the delay statistics sum in this order).
        for (std::uint32_t axis = 0; axis < axes; ++axis) {
          std::vector<sim::AppliedSetpoint> applied;
          for (const auto& a : responses[axis].applied()) {
            applied.push_back({a.cycle(), a.send_time_s(), a.arrival_time_s(), a.network_arrival_s(), a.horizon_index()});
          }
          server_.record_applied(axis, applied);
        }
        const double t = static_cast<double>(k + 1) * h;
        for (std::uint32_t axis = 0; axis < axes; ++axis) {
          server_.submit_feedback(axis, k + 1, t,
                                  {responses[axis].position_m(), responses[axis].true_position_m()});
        }
      }
      std::uint64_t lost = 0, stale = 0, horizon = 0, held = 0;
      for (const auto& response : responses) {
        lost += response.lost_setpoints();
        stale += response.stale_setpoints();
        horizon += response.horizon_cycles();
        held += response.held_cycles();
      }
      server_.record_playout(horizon, held);
      const sim::IterationRecord record = server_.end_iteration(lost, stale);
      if (cancelled) break;  // a partial iteration is not reported
      publish_iteration_log(channels_, publisher_.job_id(), job_, record);
      if (on_iteration) on_iteration(record);
      if (record.metrics.diverged) break;
    }
  } catch (...) {
    publisher_.end_job();
    throw;
  }
  publisher_.end_job();
}

}  // namespace netmc::service
