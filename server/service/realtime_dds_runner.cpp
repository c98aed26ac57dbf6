#include "server/service/realtime_dds_runner.hpp"

#include <thread>

#include "server/job/job_builder.hpp"

namespace netmc::service {
namespace {

using Clock = std::chrono::steady_clock;

double monotonic_s(Clock::time_point t) {
  return std::chrono::duration<double>(t.time_since_epoch()).count();
}

Clock::time_point at_monotonic(double seconds) {
  return Clock::time_point(
      std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds)));
}

// Lead time between announcing an iteration and its t = 0, so every axis has the BEGIN sample
// (and, in iteration 1, has built the job) before its first tick.
constexpr double kStartLeadS = 0.25;

}  // namespace

RealtimeDdsRunner::RealtimeDdsRunner(JobChannels channels, const netmc::v1::JobSpec& spec,
                                     std::uint64_t job_id, std::chrono::milliseconds axis_timeout,
                                     std::uint32_t missed_cycles_limit)
    : channels_(channels),
      job_(job::build_contour_job(spec)),
      server_(job_),
      publisher_(channels.setpoints, spec, job_id),
      axis_timeout_(axis_timeout),
      missed_cycles_limit_(missed_cycles_limit) {}

void RealtimeDdsRunner::submit(const netmc::dds::Feedback& feedback, double start_monotonic_s) {
  const std::size_t axis = feedback.axis_id();
  std::vector<sim::AppliedSetpoint> applied;
  for (const auto& a : feedback.applied()) applied.push_back({a.cycle(), a.send_time_s(), a.arrival_time_s()});
  server_.record_applied(axis, applied);
  // The feedback enters the emulated uplink when it reaches the server: real latency + netsim.
  const double received = monotonic_s(Clock::now()) - start_monotonic_s;
  server_.submit_feedback(axis, feedback.cycle(), received,
                          {feedback.position_m(), feedback.true_position_m()});
  received_[{feedback.cycle(), static_cast<std::uint32_t>(axis)}] = true;
}

void RealtimeDdsRunner::gather(std::uint32_t iteration, std::uint64_t cycle, double start_monotonic_s,
                               Clock::time_point until) {
  const auto axes = static_cast<std::uint32_t>(job_.axes.size());
  const auto complete = [&] {
    for (std::uint32_t axis = 0; axis < axes; ++axis) {
      if (!received_.count({cycle, axis})) return false;
    }
    return true;
  };
  while (!complete()) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(until - Clock::now());
    auto sample = channels_.feedback->take(std::max(left, std::chrono::milliseconds(0)));
    if (!sample) return;  // deadline: the cycle runs with the newest feedback it has
    if (sample->job_id() != publisher_.job_id() || sample->iteration() != iteration ||
        sample->axis_id() >= axes) {
      continue;
    }
    if (sample->kind() == netmc::dds::FEEDBACK_FINAL) {
      finals_[sample->axis_id()] = *sample;
      final_in_[sample->axis_id()] = true;
      continue;
    }
    submit(*sample, start_monotonic_s);
  }
}

void RealtimeDdsRunner::run(const std::function<void(const sim::IterationRecord&)>& on_iteration,
                            const std::atomic<bool>& cancel) {
  const auto axes = static_cast<std::uint32_t>(job_.axes.size());
  const std::size_t cycles = server_.cycles();
  const double h = job_.sample_period_s;
  try {
    for (std::uint32_t iteration = 1; iteration <= job_.iterations && !cancel.load(); ++iteration) {
      const Eigen::Vector2d start = server_.begin_iteration(iteration);
      const double t0 = monotonic_s(Clock::now()) + kStartLeadS;
      received_.clear();
      finals_.assign(axes, {});
      final_in_.assign(axes, false);
      for (std::uint32_t axis = 0; axis < axes; ++axis) {
        publisher_.publish(axis, iteration, 0, netmc::dds::SETPOINT_BEGIN_ITERATION, 0.0, 0.0,
                           start[static_cast<Eigen::Index>(axis)], iteration == 1, t0);
      }
      std::vector<std::size_t> last_heard(axes, 0);  // cycle of each axis's newest feedback
      bool stopped_early = false;
      for (std::size_t k = 0; k < cycles; ++k) {
        const double t = static_cast<double>(k) * h;
        gather(iteration, k, t0, at_monotonic(t0 + t + job_.deadline()));
        for (std::uint32_t axis = 0; axis < axes; ++axis) {
          if (received_.count({k, axis})) last_heard[axis] = k;
          if (k - last_heard[axis] > missed_cycles_limit_) {
            throw JobFailure("axis " + axis_name(axis) + " sent no feedback for " +
                             std::to_string(k - last_heard[axis]) + " periods (cycle " +
                             std::to_string(k) + " of iteration " + std::to_string(iteration) +
                             "; node stopped or unreachable)");
          }
        }
        // Act when the emulated uplink delivers (or at the deadline), as ContourServer decides.
        std::this_thread::sleep_until(at_monotonic(t0 + server_.compute_time(k)));
        const auto ready = Clock::now();
        const sim::CycleCommand command = server_.compute_cycle(k);
        if (command.diverged || cancel.load()) {
          stopped_early = !command.diverged;
          break;
        }
        const auto departure = Clock::now();
        const double now = monotonic_s(departure) - t0;
        for (std::uint32_t axis = 0; axis < axes; ++axis) {
          publisher_.publish(axis, iteration, k, netmc::dds::SETPOINT_COMMAND,
                             command.command[static_cast<Eigen::Index>(axis)], now, 0.0, false, 0.0);
        }
        server_.correct_compute_delay(std::chrono::duration<double>(departure - ready).count());
      }
      for (std::uint32_t axis = 0; axis < axes; ++axis) {
        publisher_.publish(axis, iteration, cycles, netmc::dds::SETPOINT_END_ITERATION, 0.0, 0.0,
                           0.0, false, 0.0);
      }
      // The finals carry the axes' downlink counters.
      const auto final_deadline = Clock::now() + axis_timeout_;
      while (std::find(final_in_.begin(), final_in_.end(), false) != final_in_.end() &&
             Clock::now() < final_deadline) {
        gather(iteration, cycles, t0, final_deadline);
      }
      std::uint64_t lost = 0, stale = 0;
      for (std::uint32_t axis = 0; axis < axes; ++axis) {
        if (!final_in_[axis]) {
          throw JobFailure("axis " + axis_name(axis) + " did not confirm the end of iteration " +
                           std::to_string(iteration) + " within " +
                           std::to_string(axis_timeout_.count()) + " ms");
        }
        lost += finals_[axis].lost_setpoints();
        stale += finals_[axis].stale_setpoints();
      }
      const sim::IterationRecord record = server_.end_iteration(lost, stale);
      if (stopped_early) break;
      publish_iteration_log(channels_.iteration_logs, publisher_.job_id(), job_, record);
      if (on_iteration) on_iteration(record);
      if (record.metrics.diverged) break;
    }
  } catch (...) {
    publisher_.end_job(axes);
    throw;
  }
  publisher_.end_job(axes);
}

}  // namespace netmc::service
